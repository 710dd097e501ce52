#include <vimlop/Video/KltFeatureTracker.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <cmath>

namespace vimlop
{

namespace
{

cv::Mat greyOf(const cv::Mat& frame)
{
  if (frame.empty())
  {
    throw Error("feature tracking: the frame is empty");
  }
  if (frame.depth() != CV_8U || (frame.channels() != 1 && frame.channels() != 3))
  {
    throw Error(formatText("feature tracking: frames must be 8-bit grey or BGR, not %d-channel "
                           "with OpenCV depth %d",
      frame.channels(), frame.depth()));
  }
  if (frame.channels() == 1)
  {
    return frame;
  }
  cv::Mat grey;
  cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
  return grey;
}

/// The grey picture with its slowly varying illumination divided out: minus
/// its local mean, over its local standard deviation (Gaussian windows of
/// `sigmaPx`), mapped to 8 bits around 128. An endoscope carries its light,
/// so a patch brightens as the scope nears it, and Lucas-Kanade, which
/// assumes constant brightness, would slide.
cv::Mat withoutIllumination(const cv::Mat& grey, double sigmaPx)
{
  cv::Mat value;
  grey.convertTo(value, CV_32F);
  cv::Mat mean;
  cv::GaussianBlur(value, mean, cv::Size(0, 0), sigmaPx);
  cv::Mat detail = value - mean;
  cv::Mat variance;
  cv::GaussianBlur(detail.mul(detail), variance, cv::Size(0, 0), sigmaPx);
  cv::Mat deviation;
  cv::sqrt(variance + 1.0f, deviation);
  cv::Mat normalised = detail / deviation;
  cv::Mat out;
  normalised.convertTo(out, CV_8U, 40.0, 128.0);
  return out;
}

} // namespace

void KltFeatureTrackerOptions::validate() const
{
  if (this->windowPx < 5 || this->windowPx % 2 == 0)
  {
    throw Error(
      formatText("feature tracking: the window must be an odd number of pixels, at least 5, not %d",
        this->windowPx));
  }
  if (this->pyramidLevels < 0 || this->pyramidLevels > 8)
  {
    throw Error(formatText(
      "feature tracking: pyramid levels must lie in [0, 8], not %d", this->pyramidLevels));
  }
  if (!(this->maxForwardBackwardPx > 0.0))
  {
    throw Error(formatText("feature tracking: the forward-backward tolerance must be positive, "
                           "not %g px",
      this->maxForwardBackwardPx));
  }
  if (!(this->cornerQuality > 0.0 && this->cornerQuality < 1.0))
  {
    throw Error(formatText(
      "feature tracking: the corner quality must lie in (0, 1), not %g", this->cornerQuality));
  }
  if (!(this->illuminationSigmaPx >= 0.0))
  {
    throw Error(
      formatText("feature tracking: the illumination scale must not be negative, not %g px",
        this->illuminationSigmaPx));
  }
  if (!(this->minCornerDistancePx >= 0.0))
  {
    throw Error(formatText("feature tracking: the corner distance must not be negative, not %g px",
      this->minCornerDistancePx));
  }
}

KltFeatureTracker::KltFeatureTracker(const KltFeatureTrackerOptions& options)
  : Options(options)
{
  this->Options.validate();
}

cv::Mat KltFeatureTracker::prepared(const cv::Mat& frame) const
{
  const cv::Mat grey = greyOf(frame);
  return this->Options.illuminationSigmaPx > 0.0
    ? withoutIllumination(grey, this->Options.illuminationSigmaPx)
    : grey.clone();
}

void KltFeatureTracker::reset(const cv::Mat& frame)
{
  this->Current = this->prepared(frame);
}

std::vector<char> KltFeatureTracker::track(
  const cv::Mat& frame, std::vector<Eigen::Vector2d>& pixels)
{
  if (this->Current.empty())
  {
    throw Error("feature tracking: no current frame (reset() first)");
  }
  const cv::Mat next = this->prepared(frame);
  if (next.size() != this->Current.size())
  {
    throw Error(formatText("feature tracking: a frame of %d x %d pixels after frames of %d x %d",
      next.cols, next.rows, this->Current.cols, this->Current.rows));
  }
  std::vector<char> kept(pixels.size(), 0);
  if (!pixels.empty())
  {
    std::vector<cv::Point2f> from;
    from.reserve(pixels.size());
    for (const Eigen::Vector2d& p : pixels)
    {
      from.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
    }
    const cv::Size window(this->Options.windowPx, this->Options.windowPx);
    const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);
    std::vector<cv::Point2f> to;
    std::vector<cv::Point2f> back;
    std::vector<unsigned char> forwardFound;
    std::vector<unsigned char> backwardFound;
    std::vector<float> error;
    cv::calcOpticalFlowPyrLK(this->Current, next, from, to, forwardFound, error, window,
      this->Options.pyramidLevels, stop);
    cv::calcOpticalFlowPyrLK(next, this->Current, to, back, backwardFound, error, window,
      this->Options.pyramidLevels, stop);
    const double maxSquared =
      this->Options.maxForwardBackwardPx * this->Options.maxForwardBackwardPx;
    for (std::size_t i = 0; i < pixels.size(); ++i)
    {
      const cv::Point2f drift = back[i] - from[i];
      const bool inside = to[i].x >= 0.0f && to[i].y >= 0.0f &&
        to[i].x <= static_cast<float>(next.cols - 1) &&
        to[i].y <= static_cast<float>(next.rows - 1);
      kept[i] = forwardFound[i] && backwardFound[i] && inside && drift.dot(drift) <= maxSquared;
      pixels[i] = { to[i].x, to[i].y };
    }
  }
  this->Current = next;
  return kept;
}

std::vector<Eigen::Vector2d> KltFeatureTracker::detect(
  int count, const std::vector<Eigen::Vector2d>& existing, const cv::Mat& mask) const
{
  if (this->Current.empty())
  {
    throw Error("feature tracking: no current frame (reset() first)");
  }
  if (!mask.empty() && mask.size() != this->Current.size())
  {
    throw Error(formatText("feature tracking: a mask of %d x %d pixels for frames of %d x %d",
      mask.cols, mask.rows, this->Current.cols, this->Current.rows));
  }
  if (count <= 0)
  {
    return {};
  }
  // The features already tracked are masked out with their neighbourhood, so
  // new corners fill the picture where the tracked ones are missing.
  cv::Mat allowed =
    mask.empty() ? cv::Mat(this->Current.size(), CV_8U, cv::Scalar(255)) : (mask != 0);
  // Nor within half a window of the border, where the window would leave
  // the picture and bias the match.
  const int margin = this->Options.windowPx / 2;
  allowed.rowRange(0, std::min(margin, allowed.rows)).setTo(0);
  allowed.rowRange(std::max(0, allowed.rows - margin), allowed.rows).setTo(0);
  allowed.colRange(0, std::min(margin, allowed.cols)).setTo(0);
  allowed.colRange(std::max(0, allowed.cols - margin), allowed.cols).setTo(0);
  const int radius = static_cast<int>(std::lround(this->Options.minCornerDistancePx));
  for (const Eigen::Vector2d& p : existing)
  {
    cv::circle(allowed,
      cv::Point(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y()))), radius,
      cv::Scalar(0), cv::FILLED);
  }
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(this->Current, corners, count, this->Options.cornerQuality,
    this->Options.minCornerDistancePx, allowed);
  std::vector<Eigen::Vector2d> found;
  found.reserve(corners.size());
  for (const cv::Point2f& c : corners)
  {
    found.emplace_back(c.x, c.y);
  }
  return found;
}

} // namespace vimlop
