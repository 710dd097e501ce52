#include <vimlop/Pipeline/TrackedVideoWriter.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Video/FrameBanner.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <cmath>

namespace vimlop
{

struct TrackedVideoWriter::Internals
{
  PinholeCamera Camera;
  std::string Path;
  double Fps = 30.0;
  cv::VideoWriter Video;
  int Written = 0;
};

TrackedVideoWriter::TrackedVideoWriter(
  const PinholeCamera& camera, const std::string& path, double fps)
{
  camera.validate();
  if (!(fps > 0.0) || !std::isfinite(fps))
  {
    throw Error(formatText("tracked video: the rate must be positive, not %g fps", fps));
  }
  this->d = std::unique_ptr<Internals>(new Internals{ camera, path, fps, {}, 0 });
}

TrackedVideoWriter::~TrackedVideoWriter() = default;

int TrackedVideoWriter::framesWritten() const
{
  return this->d->Written;
}

cv::Mat TrackedVideoWriter::write(const cv::Mat& frame, const TrackedFrame& tracked,
  const std::string& frameName, const std::vector<ModelContourPoint>& modelContours,
  double contourErrorPx)
{
  Internals& s = *this->d;
  if (frame.cols != s.Camera.widthPx || frame.rows != s.Camera.heightPx || frame.type() != CV_8UC3)
  {
    throw Error(formatText("tracked video: a frame of %d x %d pixels (type %d), but the camera "
                           "is %d x %d and frames are 8-bit BGR",
      frame.cols, frame.rows, frame.type(), s.Camera.widthPx, s.Camera.heightPx));
  }
  const BannerColour colour = tracked.state == TrackingState::Tracking ? BannerColour::Green
    : tracked.state == TrackingState::Degraded                         ? BannerColour::Amber
                                                                       : BannerColour::Red;
  const cv::Scalar contourColour = tracked.state == TrackingState::Tracking
    ? cv::Scalar(80, 255, 80)
    : tracked.state == TrackingState::Degraded ? cv::Scalar(0, 200, 255)
                                               : cv::Scalar(60, 60, 255);
  cv::Mat picture = frame.clone();
  for (const ModelContourPoint& p : modelContours)
  {
    cv::circle(picture,
      cv::Point(
        static_cast<int>(std::lround(p.pixel.x())), static_cast<int>(std::lround(p.pixel.y()))),
      1, contourColour, cv::FILLED);
  }
  std::string text = frameName + ": " + toString(tracked.state);
  if (!tracked.reason.empty())
  {
    text += " (" + tracked.reason + ")";
  }
  if (std::isfinite(contourErrorPx))
  {
    text += formatText("; contours %.1f px", contourErrorPx);
  }
  const cv::Mat framed = underBanner(picture, colour, text);
  if (!s.Video.isOpened())
  {
    s.Video.open(s.Path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), s.Fps, framed.size());
    if (!s.Video.isOpened())
    {
      throwFileError(s.Path, "cannot write the video");
    }
  }
  s.Video.write(framed);
  ++s.Written;
  return framed;
}

} // namespace vimlop
