#ifndef vimlop_EndoscopeTrajectory_h
#define vimlop_EndoscopeTrajectory_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/RegistrationModel.h>

#include "VIMLOPRenderingModule.h"

#include <cstdint>
#include <vector>

namespace vimlop
{

/**
 * @brief Options of a simulated endoscope path through the airway; lengths in
 * mm (CT frame), angles in degrees.
 */
struct EndoscopeTrajectoryOptions
{
  /// Number of camera poses (default 30, the paper's sequence length).
  int frames = 30;
  /// Advance along the passage between frames, mm (default 0.5: enough
  /// parallax for SfM over a few frames, small enough to track features).
  double stepMm = 0.5;
  /// Least distance of every optical centre to the wall, mm (default 2, the
  /// radius of a 4 mm endoscope).
  double minClearanceMm = 2.0;
  /// Amplitude of the smooth sideways sway of the scope tip, mm (default 0.6):
  /// a hand-held scope never moves straight, and the sideways motion gives
  /// SfM parallax where pure forward motion gives little.
  double swayAmplitudeMm = 0.6;
  /// Period of the sway, frames (default 24).
  double swayPeriodFrames = 24.0;
  /// Amplitude of the view direction's wobble about the passage axis, degrees (default 4).
  double viewSwayDeg = 4.0;
  /// Free length required beyond the last camera along the passage, mm
  /// (default 8), so that the scope looks down an open passage, not at a wall.
  double lookAheadMm = 8.0;
  /// Roll of the scope: negative (default) for any roll about the view axis;
  /// otherwise the image "up" stays within this many degrees of anatomical
  /// superior (+z, LPS), as when a surgeon holds the scope upright.
  double uprightRollDeg = -1.0;
  /// Camera used to check that every view shows occluding contours.
  PinholeCamera intrinsics;
  /// Least number of visible occluding-contour samples (1 px apart) in each
  /// view (default 150; 0 skips the check).
  int minContourSamples = 150;
  /// Random start positions tried before giving up (default 4000).
  int maxAttempts = 4000;
  /// Hand tremor: each optical centre is moved off the smooth path by an
  /// independent random offset (isotropic Gaussian) whose root-mean-square
  /// length is this, mm (default 0: none). White, not smooth, because
  /// physiological tremor lies at 8-12 Hz, close to the 15 Hz Nyquist limit
  /// of 30 fps video: successive frames see nearly independent phases. A
  /// realistic value: 0.1-0.5 mm (an estimate, Documentation/Simulation.md).
  /// Finite and at least 0.
  double jitterMm = 0.0;
  /// Hand tremor of the view: each view turned by an independent random
  /// rotation (isotropic Gaussian rotation vector) whose root-mean-square
  /// angle is this, degrees (default 0: none; about 0.5, an estimate).
  /// Finite and at least 0.
  double jitterDeg = 0.0;
  /// Curved paths: the passage axis turns at this rate along the path,
  /// degrees per mm (default 0: a straight axis, as before), about an axis
  /// across the passage chosen, like the passage axis, to keep farthest from
  /// the walls, so that the path follows a curved passage. Finite and at least 0.
  double turnDegPerMm = 0.0;

  /**
   * @brief Checks the options (the intrinsics apart, which the caller may
   * set later).
   * @throws vimlop::Error naming the first problem.
   */
  void validate() const;
};

/**
 * @brief A smooth endoscope path inside the airway of `model`, reproducible
 * from `seed`: camera-to-CT poses, one per frame.
 *
 * The path follows a straight passage axis (the longest free direction from
 * a random start with enough clearance, so it runs along the passage) with a
 * smooth sideways sway; the scope looks along the axis with a small smooth
 * wobble and roll. With `turnDegPerMm` the axis is an arc instead, turning at
 * that rate; with `jitterMm` and `jitterDeg` each pose gets an independent
 * random tremor on top. Every optical centre is inside the airway at least
 * `minClearanceMm` from the wall, and every view shows at least
 * `minContourSamples` visible occluding-contour samples.
 *
 * @throws vimlop::Error when no such path is found within `maxAttempts`
 * starts, or for invalid options.
 */
VIMLOPRENDERING_EXPORT std::vector<CameraPose> makeEndoscopeTrajectory(
  const RegistrationModel& model, const EndoscopeTrajectoryOptions& options, std::uint64_t seed);

} // namespace vimlop

#endif
