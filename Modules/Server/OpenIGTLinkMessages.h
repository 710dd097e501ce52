#ifndef vimlop_OpenIGTLinkMessages_h
#define vimlop_OpenIGTLinkMessages_h

// Private to the Server module: the OpenIGTLink messages a pose server sends,
// each packed with its timestamp (seconds on the wall clock) into the bytes
// that go on the wire. OpenIGTLink's headers stay in the .cxx.

#include <vimlop/Server/ServedPoses.h>

#include <Eigen/Core>

#include <string>

namespace vimlop::igtlmessages
{

/// @brief A TRANSFORM of `m` (its upper 3 x 4 block, as floats).
std::string packTransform(const std::string& name, const Eigen::Matrix4d& m, double timeS);

/// @brief An IMAGE of a frame's picture: RGB, one slice, j downward (rows top first).
std::string packImage(const std::string& device, const FramePicture& picture, double timeS);

/// @brief A STATUS for a frame without a pose: the camera device is not present (TrackingLost).
std::string packTrackingLost(
  const std::string& device, const FrameWithoutPose& frame, double timeS);

/// @brief A STATUS after a pose its tracker does not vouch for (TrackingDegraded).
std::string packTrackingDegraded(
  const std::string& device, const DegradedPose& frame, double timeS);

/// @brief A STATUS with a registration's verdict (OK, or RegistrationFlagged).
std::string packStatus(const std::string& device, const PoseVerdict& verdict, double timeS);

} // namespace vimlop::igtlmessages

#endif
