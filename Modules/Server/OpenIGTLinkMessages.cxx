#include "OpenIGTLinkMessages.h"

#include <igtlImageMessage.h>
#include <igtlStatusMessage.h>
#include <igtlTimeStamp.h>
#include <igtlTransformMessage.h>

#include <cstring>

namespace vimlop::igtlmessages
{

namespace
{

std::string packed(igtl::MessageBase& message, double timeS)
{
  igtl::TimeStamp::Pointer stamp = igtl::TimeStamp::New();
  stamp->SetTime(timeS);
  message.SetTimeStamp(stamp);
  message.Pack();
  return std::string(
    static_cast<const char*>(message.GetPackPointer()), static_cast<size_t>(message.GetPackSize()));
}

} // namespace

std::string packTransform(const std::string& name, const Eigen::Matrix4d& m, double timeS)
{
  igtl::Matrix4x4 matrix;
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      matrix[i][j] = static_cast<float>(m(i, j));
    }
  }
  igtl::TransformMessage::Pointer message = igtl::TransformMessage::New();
  message->SetDeviceName(name.c_str());
  message->SetMatrix(matrix);
  return packed(*message, timeS);
}

std::string packImage(const std::string& device, const FramePicture& picture, double timeS)
{
  igtl::ImageMessage::Pointer message = igtl::ImageMessage::New();
  message->SetDeviceName(device.c_str());
  message->SetDimensions(picture.widthPx, picture.heightPx, 1);
  message->SetSpacing(1.0f, 1.0f, 1.0f);
  message->SetScalarTypeToUint8();
  message->SetNumComponents(3);
  igtl::Matrix4x4 matrix;
  igtl::IdentityMatrix(matrix);
  matrix[1][1] = -1.0f;
  matrix[2][2] = -1.0f;
  message->SetMatrix(matrix);
  message->AllocateScalars();
  std::memcpy(message->GetScalarPointer(), picture.rgb.data(), picture.rgb.size());
  return packed(*message, timeS);
}

namespace
{

/// A STATUS message: every status VIMLOP sends is this with its own fields.
std::string packStatusMessage(const std::string& device, int code, int subCode,
  const std::string& errorName, const std::string& text, double timeS)
{
  igtl::StatusMessage::Pointer message = igtl::StatusMessage::New();
  message->SetDeviceName(device.c_str());
  message->SetCode(code);
  message->SetSubCode(subCode);
  message->SetErrorName(errorName.c_str());
  message->SetStatusString(text.c_str());
  return packed(*message, timeS);
}

/// ": reason", or nothing.
std::string because(const std::string& reason)
{
  return reason.empty() ? std::string() : ": " + reason;
}

} // namespace

std::string packTrackingLost(const std::string& device, const FrameWithoutPose& frame, double timeS)
{
  return packStatusMessage(device, igtl::StatusMessage::STATUS_NOT_PRESENT, frame.frameId,
    "TrackingLost",
    "frame " + std::to_string(frame.frameId) + " has no pose" + because(frame.reason), timeS);
}

std::string packTrackingDegraded(const std::string& device, const DegradedPose& frame, double timeS)
{
  // An error, like a flagged registration's: do not navigate with the pose as it is.
  return packStatusMessage(device, igtl::StatusMessage::STATUS_UNKNOWN_ERROR, frame.frameId,
    "TrackingDegraded",
    "frame " + std::to_string(frame.frameId) + "'s pose is degraded" + because(frame.reason),
    timeS);
}

std::string packStatus(const std::string& device, const PoseVerdict& verdict, double timeS)
{
  return packStatusMessage(device,
    verdict.flagged ? igtl::StatusMessage::STATUS_UNKNOWN_ERROR : igtl::StatusMessage::STATUS_OK, 0,
    verdict.flagged ? "RegistrationFlagged" : "", verdict.text, timeS);
}

} // namespace vimlop::igtlmessages
