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
};

/**
 * @brief A smooth endoscope path inside the airway of `model`, reproducible
 * from `seed`: camera-to-CT poses, one per frame.
 *
 * The path follows a straight passage axis (the longest free direction from
 * a random start with enough clearance, so it runs along the passage) with a
 * smooth sideways sway; the scope looks along the axis with a small smooth
 * wobble and roll. Every optical centre is inside the airway at least
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
