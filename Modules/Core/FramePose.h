#ifndef vimlop_FramePose_h
#define vimlop_FramePose_h

#include <vimlop/Core/CameraPose.h>

#include <vector>

namespace vimlop
{

/**
 * @brief The pose of one video frame's camera, identified by the frame's id
 * (its index in the input sequence unless the input numbers frames itself).
 */
struct FramePose
{
  int frameId = 0;
  CameraPose cameraToWorld;
};

/// @brief Farthest a camera may lie from the origin of its world (the CT), mm:
/// 1 km, far beyond any scanner, and far inside the float range that the
/// OpenIGTLink messages carry (a translation above 3.4e38 became -inf).
constexpr double maxFramePoseDistanceMm = 1e6;

/**
 * @brief Checks poses before they are used or sent: every frame id once, and
 * every camera finite and within maxFramePoseDistanceMm of the origin.
 * @throws vimlop::Error naming the first bad pose by its index, e.g. "pose 3:
 * frame id 7 repeats pose 1's".
 */
void checkFramePoses(const std::vector<FramePose>& poses);

} // namespace vimlop

#endif
