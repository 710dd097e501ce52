#ifndef vimlop_TrackedPoseTable_h
#define vimlop_TrackedPoseTable_h

#include <vimlop/Core/FramePose.h>

#include <string>
#include <vector>

namespace vimlop
{

/// @brief One tracked frame as the tracked-pose table holds it.
struct TrackedPoseRow
{
  /// The frame's id and camera-to-CT pose (for a lost frame, the prediction).
  FramePose pose;
  /// "tracking", "degraded" or "lost".
  std::string state;
  /// From the decoded frame to its pose, ms.
  double latencyMs = 0.0;
};

/**
 * @brief Writes the tracked frames as a VTK XML table (.vtt), one row per
 * frame in their order, for VTK pipelines and navigation software: the
 * columns of camera-poses.vtt ("FrameId"; "CameraToCT", the 4x4 camera-to-CT
 * matrix row-major in 16 components, OpenCV camera axes, mm), then "State"
 * (a string) and "LatencyMs". Lost frames are rows too, at the prediction:
 * filter on State before showing a pose.
 * @throws vimlop::Error when the file cannot be written.
 */
void writeTrackedPoseTable(const std::vector<TrackedPoseRow>& rows, const std::string& path);

} // namespace vimlop

#endif
