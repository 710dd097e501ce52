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

std::string packTrackingLost(const std::string& device, const FrameWithoutPose& frame, double timeS)
{
  igtl::StatusMessage::Pointer message = igtl::StatusMessage::New();
  message->SetDeviceName(device.c_str());
  message->SetCode(igtl::StatusMessage::STATUS_NOT_PRESENT);
  message->SetSubCode(frame.frameId);
  message->SetErrorName("TrackingLost");
  message->SetStatusString(("frame " + std::to_string(frame.frameId) + " has no pose" +
    (frame.reason.empty() ? std::string() : ": " + frame.reason))
                             .c_str());
  return packed(*message, timeS);
}

std::string packTrackingDegraded(const std::string& device, const DegradedPose& frame, double timeS)
{
  igtl::StatusMessage::Pointer message = igtl::StatusMessage::New();
  message->SetDeviceName(device.c_str());
  // An error, like a flagged registration's: do not navigate with the pose as it is.
  message->SetCode(igtl::StatusMessage::STATUS_UNKNOWN_ERROR);
  message->SetSubCode(frame.frameId);
  message->SetErrorName("TrackingDegraded");
  message->SetStatusString(("frame " + std::to_string(frame.frameId) + "'s pose is degraded" +
    (frame.reason.empty() ? std::string() : ": " + frame.reason))
                             .c_str());
  return packed(*message, timeS);
}

std::string packStatus(const std::string& device, const PoseVerdict& verdict, double timeS)
{
  igtl::StatusMessage::Pointer message = igtl::StatusMessage::New();
  message->SetDeviceName(device.c_str());
  message->SetCode(
    verdict.flagged ? igtl::StatusMessage::STATUS_UNKNOWN_ERROR : igtl::StatusMessage::STATUS_OK);
  message->SetSubCode(0);
  message->SetErrorName(verdict.flagged ? "RegistrationFlagged" : "");
  message->SetStatusString(verdict.text.c_str());
  return packed(*message, timeS);
}

} // namespace vimlop::igtlmessages
