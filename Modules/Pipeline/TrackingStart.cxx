#include <vimlop/Pipeline/TrackingStart.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Results/RegistrationRecordIO.h>
#include <vimlop/Video/FieldOfView.h>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>

namespace vimlop
{

TrackingStart TrackingStart::fromResult(const std::string& folder)
{
  const RegistrationRecord record = readRegistrationRecord(folder);
  const std::vector<VideoFrame>& frames = record.data.frames;
  if (frames.empty())
  {
    throwFileError(folder, "the result registered no frame to start tracking from");
  }
  // The last frame of the video that was registered: tracking goes on from it.
  const auto last = std::max_element(frames.begin(), frames.end(),
    [](const VideoFrame& a, const VideoFrame& b) { return a.frameId < b.frameId; });
  const std::size_t j = static_cast<std::size_t>(last - frames.begin());
  if (j >= record.frameImages.size() || record.frameImages[j].empty())
  {
    throwFileError(folder,
      "the result holds no picture of its last registered frame (" + std::to_string(last->frameId) +
        "), which tracking starts on");
  }
  const std::string picture = (std::filesystem::path(folder) / record.frameImages[j]).string();
  // A registered frame's picture, empty when it cannot be read (asked
  // first: OpenCV would print its own warning for a missing file).
  const auto readPicture = [](const std::string& path)
  {
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec) ? cv::imread(path, cv::IMREAD_COLOR)
                                                      : cv::Mat();
  };
  TrackingStart start;
  start.frame = readPicture(picture);
  if (start.frame.empty())
  {
    throwFileError(picture, "cannot read the picture of the last registered frame");
  }
  // The field stop as the registered frames show it: a live stream has no
  // sequence to find it on before its first frame.
  std::vector<cv::Mat> registered;
  for (std::size_t i = 0; i < record.frameImages.size(); ++i)
  {
    const std::string& image = record.frameImages[i];
    const cv::Mat other = i == j ? start.frame
      : image.empty()            ? cv::Mat()
                                 : readPicture((std::filesystem::path(folder) / image).string());
    if (!other.empty() && other.size() == start.frame.size())
    {
      registered.push_back(other);
    }
  }
  start.fieldOfViewMask = FieldOfView::ofSequence(registered, FieldOfViewOptions()).mask();
  start.modelCT = record.model;
  start.intrinsics = last->intrinsics;
  start.cameraToCT = record.result.sfmToCT.apply(last->cameraToSfm);
  start.frameId = last->frameId;
  start.contourErrorPx = record.result.contourErrorPx;
  start.frameSource = j < record.frameSources.size() ? record.frameSources[j] : std::string();
  if (record.confidence && record.confidence->failure)
  {
    start.failureReason =
      record.confidence->reason.empty() ? "flagged as a failure" : record.confidence->reason;
  }
  return start;
}

} // namespace vimlop
