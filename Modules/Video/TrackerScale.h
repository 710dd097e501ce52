#ifndef vimlop_TrackerScale_h
#define vimlop_TrackerScale_h

#include <vimlop/Video/TrackerTrajectory.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace vimlop
{

/// @brief Options of the initial scale from an electromagnetic tracker (V14).
struct TrackerScaleOptions
{
  /// Temporal smoothing of the tracker positions, seconds (default 0.1).
  double smoothingS = 0.1;
  /// Least length of the tracked chords the trajectory length is summed
  /// over, mm (default 2). Summing over every frame would add the tracker's
  /// noise to the length (|a + noise| is longer than |a| on average, and the
  /// more so the shorter a is); chords of a few mm keep that bias small.
  double minChordMm = 2.0;
  /// Least number of frames matched to the tracker (default 3).
  int minFrames = 3;
};

/// @brief The scale and what went into it.
struct TrackerScaleResult
{
  /// SfM units to mm: tracked length / SfM length over the same frames.
  double scale = 1.0;
  double trackerLengthMm = 0.0;
  double sfmLength = 0.0;
  /// Frames used, and frames dropped because the tracker did not cover their time
  /// or SfM did not register them.
  std::vector<int> framesUsed;
  std::vector<int> framesDropped;
  /// What the user should know (dropped frames, short overlap).
  std::vector<std::string> warnings;
};

/**
 * @brief Checks that the tracker recorded while at least one frame was taken.
 * @throws vimlop::Error naming both time spans when no frame time lies
 * within the tracker's.
 */
void checkTrackerOverlap(const TrackerTrajectory& tracker, const std::vector<double>& frameTimesS);

/**
 * @brief Scales SfM so that the camera trajectory is as long as the tracked
 * one (V14): matches each frame to the tracker by time, sums chord lengths of
 * both trajectories over the same frames, and returns their ratio.
 *
 * @param frameTimesS time of each frame on the tracker's clock, seconds.
 * @param sfmCentres optical centre of each frame in the SfM frame; a
 * non-finite entry marks a frame SfM did not register.
 * @throws vimlop::Error when the tracker and the frames do not overlap in
 * time, fewer than `minFrames` frames match, or either trajectory has no
 * length (no motion).
 */
TrackerScaleResult estimateTrackerScale(const TrackerTrajectory& tracker,
  const std::vector<double>& frameTimesS, const std::vector<Eigen::Vector3d>& sfmCentres,
  const TrackerScaleOptions& options = TrackerScaleOptions());

} // namespace vimlop

#endif
