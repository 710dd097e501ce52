#include <vimlop/Pipeline/FrameContourCheck.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/KdTree2D.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Core/VisibleModelContours.h>
#include <vimlop/Video/OccludingContourDetector.h>

#include <algorithm>
#include <utility>

namespace vimlop
{

struct FrameContourCheck::Internals
{
  RegistrationModel Model;
  PinholeCamera Camera;
  cv::Mat Mask;
  OccludingContourDetector Detector;
  ContourMatchOptions Matching;
};

FrameContourCheck::FrameContourCheck(const RegistrationModel& model, const PinholeCamera& camera,
  const cv::Mat& fieldOfViewMask, const ContourDetectionOptions& detection,
  const ContourMatchOptions& matching)
{
  camera.validate();
  if (!fieldOfViewMask.empty() &&
    (fieldOfViewMask.cols != camera.widthPx || fieldOfViewMask.rows != camera.heightPx))
  {
    throw Error(formatText("contour check: a field-of-view mask of %d x %d pixels, but the "
                           "camera is %d x %d",
      fieldOfViewMask.cols, fieldOfViewMask.rows, camera.widthPx, camera.heightPx));
  }
  this->d = std::unique_ptr<Internals>(
    new Internals{ model, camera, fieldOfViewMask, OccludingContourDetector(detection), matching });
}

FrameContourCheck::~FrameContourCheck() = default;

const PinholeCamera& FrameContourCheck::camera() const
{
  return this->d->Camera;
}

const RegistrationModel& FrameContourCheck::model() const
{
  return this->d->Model;
}

FrameContourAgreement FrameContourCheck::check(
  const cv::Mat& frame, const CameraPose& cameraToCT) const
{
  return this->agreement(this->detect(frame), cameraToCT);
}

std::vector<ContourPoint> FrameContourCheck::detect(const cv::Mat& frame) const
{
  const Internals& s = *this->d;
  if (frame.cols != s.Camera.widthPx || frame.rows != s.Camera.heightPx)
  {
    throw Error(formatText("contour check: a frame of %d x %d pixels, but the camera is %d x %d",
      frame.cols, frame.rows, s.Camera.widthPx, s.Camera.heightPx));
  }
  return s.Detector.detect(frame, s.Mask);
}

FrameContourAgreement FrameContourCheck::agreement(
  const std::vector<ContourPoint>& detected, const CameraPose& cameraToCT) const
{
  const Internals& s = *this->d;
  FrameContourAgreement agreement;
  agreement.modelContours = visibleModelContours(s.Model, s.Camera, cameraToCT);
  agreement.detected = static_cast<int>(detected.size());
  if (detected.empty() || agreement.modelContours.empty())
  {
    return agreement;
  }
  std::vector<Eigen::Vector2d> pixels;
  pixels.reserve(agreement.modelContours.size());
  for (const ModelContourPoint& p : agreement.modelContours)
  {
    pixels.push_back(p.pixel);
  }
  const KdTree2D tree(std::move(pixels));
  const std::vector<ContourMatch> matches =
    matchContours(detected, agreement.modelContours, tree, s.Matching);
  std::vector<double> errors;
  for (const ContourMatch& m : matches)
  {
    if (m.model >= 0)
    {
      errors.push_back(m.errorPx.norm());
    }
  }
  agreement.matched = static_cast<int>(errors.size());
  if (errors.empty())
  {
    return agreement;
  }
  agreement.medianErrorPx = summarize(std::move(errors)).median;
  const double limitPx = std::max(2.0, 3.0 * agreement.medianErrorPx);
  for (const ContourMatch& m : matches)
  {
    if (m.model >= 0 && m.errorPx.norm() <= limitPx)
    {
      const ModelContourPoint& y = agreement.modelContours[static_cast<std::size_t>(m.model)];
      const ContourPoint& x = detected[static_cast<std::size_t>(m.video)];
      agreement.pairs.push_back({ 0, y.point, y.normal, x.pixel, x.normal });
    }
  }
  return agreement;
}

} // namespace vimlop
