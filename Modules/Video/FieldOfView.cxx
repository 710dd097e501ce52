#include <vimlop/Video/FieldOfView.h>

#include <vimlop/Core/Error.h>

#include <Eigen/Dense>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>

namespace vimlop
{

namespace
{

void checkSize(int widthPx, int heightPx)
{
  if (widthPx <= 0 || heightPx <= 0)
  {
    throw Error("field of view: need a positive frame size");
  }
}

void checkMargin(double marginPx)
{
  if (!(marginPx >= 0.0) || !std::isfinite(marginPx))
  {
    throw Error("field of view: the margin must be a finite non-negative number of pixels");
  }
}

/// Erodes a 0/255 mask by a disc of this radius: a pixel stays valid when
/// every pixel within the radius is valid. A distance transform does it
/// for any radius, where a structuring element would need one per radius.
cv::Mat erodeBy(const cv::Mat& mask, double marginPx)
{
  if (marginPx <= 0.0)
  {
    return mask.clone();
  }
  // Pixels outside the frame count as valid: the image border is the
  // detector's own (borderPx), not the field stop's.
  cv::Mat padded;
  cv::copyMakeBorder(mask, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(255));
  cv::Mat distance;
  cv::distanceTransform(padded, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::Mat inner = distance(cv::Rect(1, 1, mask.cols, mask.rows));
  cv::Mat eroded = inner > marginPx;
  return eroded;
}

} // namespace

FieldOfView FieldOfView::everything(int widthPx, int heightPx)
{
  checkSize(widthPx, heightPx);
  FieldOfView view;
  view.Mask = cv::Mat(heightPx, widthPx, CV_8U, cv::Scalar(255));
  return view;
}

FieldOfView FieldOfView::circle(
  int widthPx, int heightPx, double centreUPx, double centreVPx, double radiusPx, double marginPx)
{
  checkSize(widthPx, heightPx);
  checkMargin(marginPx);
  if (!(radiusPx > 0.0) || !std::isfinite(radiusPx) || !std::isfinite(centreUPx) ||
    !std::isfinite(centreVPx))
  {
    throw Error("field of view: a circle needs a finite centre and a positive radius, pixels");
  }
  FieldOfView view;
  view.Mask = cv::Mat(heightPx, widthPx, CV_8U, cv::Scalar(0));
  const double inner = radiusPx - marginPx;
  for (int v = 0; v < heightPx; ++v)
  {
    unsigned char* row = view.Mask.ptr<unsigned char>(v);
    for (int u = 0; u < widthPx; ++u)
    {
      row[u] = std::hypot(u - centreUPx, v - centreVPx) < inner ? 255 : 0;
    }
  }
  view.Everything = cv::countNonZero(view.Mask) == widthPx * heightPx;
  view.Circular = true;
  view.CentreUPx = centreUPx;
  view.CentreVPx = centreVPx;
  view.RadiusPx = radiusPx;
  return view;
}

FieldOfView FieldOfView::fromFile(
  const std::string& path, int widthPx, int heightPx, double marginPx)
{
  checkSize(widthPx, heightPx);
  checkMargin(marginPx);
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(path, ignored))
  {
    throw Error("field of view: cannot read the mask image '" + path + "': no such file");
  }
  const cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (image.empty())
  {
    throw Error("field of view: cannot read the mask image '" + path + "'");
  }
  if (image.cols != widthPx || image.rows != heightPx)
  {
    throw Error("field of view: the mask image '" + path + "' is " + std::to_string(image.cols) +
      "x" + std::to_string(image.rows) + " px, the frames are " + std::to_string(widthPx) + "x" +
      std::to_string(heightPx));
  }
  const cv::Mat white = image > 0;
  if (cv::countNonZero(white) == 0)
  {
    throw Error("field of view: the mask image '" + path + "' has no white (valid) pixel");
  }
  FieldOfView view;
  view.Mask = erodeBy(white, marginPx);
  view.Everything = cv::countNonZero(view.Mask) == widthPx * heightPx;
  return view;
}

FieldOfView FieldOfView::detect(
  const std::vector<cv::Mat>& frames, const FieldOfViewOptions& options)
{
  checkMargin(options.marginPx);
  if (frames.empty())
  {
    throw Error("field of view: no frames to detect the field stop in");
  }
  const int w = frames.front().cols;
  const int h = frames.front().rows;
  checkSize(w, h);
  // The brightest value of each pixel over the frames: anatomy moves and is
  // lit somewhere, the field stop's border is black in every frame. The
  // median removes sensor noise, whose maximum over many frames is large.
  cv::Mat brightest(h, w, CV_8U, cv::Scalar(0));
  for (const cv::Mat& frame : frames)
  {
    if (frame.cols != w || frame.rows != h || frame.depth() != CV_8U ||
      (frame.channels() != 1 && frame.channels() != 3))
    {
      throw Error("field of view: the frames must be 8-bit grey or BGR pictures of one size");
    }
    cv::Mat grey;
    if (frame.channels() == 3)
    {
      cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
    }
    else
    {
      grey = frame;
    }
    cv::Mat filtered;
    cv::medianBlur(grey, filtered, 5);
    cv::max(brightest, filtered, brightest);
  }
  const cv::Mat bright = brightest > options.autoThresholdGrey;
  cv::Mat labels;
  cv::Mat stats;
  cv::Mat centroids;
  const int components = cv::connectedComponentsWithStats(bright, labels, stats, centroids, 8);
  int largest = 0;
  for (int c = 1; c < components; ++c)
  {
    if (largest == 0 ||
      stats.at<int>(c, cv::CC_STAT_AREA) > stats.at<int>(largest, cv::CC_STAT_AREA))
    {
      largest = c;
    }
  }
  if (largest == 0)
  {
    throw Error("field of view: every frame is dark; no field of view to detect");
  }
  // Filled: dark anatomy inside the field stop (a far lumen) stays valid.
  std::vector<std::vector<cv::Point>> outlines;
  cv::findContours(labels == largest, outlines, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  size_t outer = 0;
  for (size_t k = 1; k < outlines.size(); ++k)
  {
    if (cv::contourArea(outlines[k]) > cv::contourArea(outlines[outer]))
    {
      outer = k;
    }
  }
  cv::Mat filled(h, w, CV_8U, cv::Scalar(0));
  cv::drawContours(filled, outlines, static_cast<int>(outer), cv::Scalar(255), cv::FILLED);
  const double borderFraction = 1.0 - static_cast<double>(cv::countNonZero(filled)) / (w * h);
  if (borderFraction < options.autoMinBorderFraction)
  {
    return everything(w, h);
  }
  FieldOfView view;
  view.Mask = erodeBy(filled, options.marginPx);
  view.Everything = false;
  // A circle fitted (algebraically) to the outline where it is not the
  // image's border; kept when the outline is close to it.
  std::vector<Eigen::Vector2d> edge;
  for (const cv::Point& p : outlines[outer])
  {
    if (p.x > 0 && p.y > 0 && p.x < w - 1 && p.y < h - 1)
    {
      edge.emplace_back(p.x, p.y);
    }
  }
  if (edge.size() >= 20)
  {
    Eigen::MatrixXd a(static_cast<Eigen::Index>(edge.size()), 3);
    Eigen::VectorXd b(static_cast<Eigen::Index>(edge.size()));
    for (size_t k = 0; k < edge.size(); ++k)
    {
      const auto i = static_cast<Eigen::Index>(k);
      a(i, 0) = edge[k].x();
      a(i, 1) = edge[k].y();
      a(i, 2) = 1.0;
      b(i) = edge[k].squaredNorm();
    }
    const Eigen::Vector3d x = a.colPivHouseholderQr().solve(b);
    const Eigen::Vector2d centre(0.5 * x(0), 0.5 * x(1));
    const double r2 = x(2) + centre.squaredNorm();
    if (r2 > 0.0)
    {
      const double radius = std::sqrt(r2);
      double sum2 = 0.0;
      for (const Eigen::Vector2d& p : edge)
      {
        const double e = (p - centre).norm() - radius;
        sum2 += e * e;
      }
      if (std::sqrt(sum2 / edge.size()) < 1.5)
      {
        // The outline runs along the last bright pixels; the edge lies half a pixel out.
        view.Circular = true;
        view.CentreUPx = centre.x();
        view.CentreVPx = centre.y();
        view.RadiusPx = radius + 0.5;
      }
    }
  }
  return view;
}

FieldOfView FieldOfView::ofSequence(
  const std::vector<cv::Mat>& frames, const FieldOfViewOptions& options)
{
  if (frames.empty())
  {
    throw Error("field of view: no frames");
  }
  const int w = frames.front().cols;
  const int h = frames.front().rows;
  switch (options.mode)
  {
    case FieldStopMode::None:
      return everything(w, h);
    case FieldStopMode::Auto:
      return detect(frames, options);
    case FieldStopMode::File:
      return fromFile(options.maskFile, w, h, options.marginPx);
    case FieldStopMode::Circle:
      return circle(w, h, options.centreUPx, options.centreVPx, options.radiusPx, options.marginPx);
  }
  return everything(w, h);
}

double FieldOfView::validFraction() const
{
  if (this->Mask.empty())
  {
    return 1.0;
  }
  return static_cast<double>(cv::countNonZero(this->Mask)) / (this->Mask.cols * this->Mask.rows);
}

bool FieldOfView::contains(double uPx, double vPx) const
{
  const int u = static_cast<int>(std::lround(uPx));
  const int v = static_cast<int>(std::lround(vPx));
  if (this->Mask.empty() || u < 0 || v < 0 || u >= this->Mask.cols || v >= this->Mask.rows)
  {
    return false;
  }
  return this->Mask.at<unsigned char>(v, u) != 0;
}

FieldOfViewOptions FieldOfViewOptions::fromText(
  const std::string& text, const FieldOfViewOptions& base)
{
  FieldOfViewOptions o = base;
  const std::string circlePrefix = "circle:";
  if (text == "none")
  {
    o.mode = FieldStopMode::None;
  }
  else if (text == "auto")
  {
    o.mode = FieldStopMode::Auto;
  }
  else if (text.rfind(circlePrefix, 0) == 0)
  {
    std::istringstream in(text.substr(circlePrefix.size()));
    double values[3] = { 0.0, 0.0, 0.0 };
    char comma1 = 0;
    char comma2 = 0;
    in >> values[0] >> comma1 >> values[1] >> comma2 >> values[2];
    if (!in || comma1 != ',' || comma2 != ',' || !(in >> std::ws).eof() ||
      !std::isfinite(values[0]) || !std::isfinite(values[1]) || !(values[2] > 0.0) ||
      !std::isfinite(values[2]))
    {
      throw Error(
        "field stop: expected circle:U,V,R (centre and a positive radius, pixels), got '" + text +
        "'");
    }
    o.mode = FieldStopMode::Circle;
    o.centreUPx = values[0];
    o.centreVPx = values[1];
    o.radiusPx = values[2];
  }
  else if (text.empty())
  {
    throw Error("field stop: expected none, auto, circle:U,V,R or a mask image file, got nothing");
  }
  else
  {
    o.mode = FieldStopMode::File;
    o.maskFile = text;
  }
  return o;
}

std::string FieldOfViewOptions::toText() const
{
  switch (this->mode)
  {
    case FieldStopMode::None:
      return "none";
    case FieldStopMode::Auto:
      return "auto";
    case FieldStopMode::File:
      return this->maskFile;
    case FieldStopMode::Circle:
    {
      std::ostringstream out;
      out << "circle:" << this->centreUPx << "," << this->centreVPx << "," << this->radiusPx;
      return out.str();
    }
  }
  return "auto";
}

const char* fieldStopModeName(FieldStopMode mode)
{
  switch (mode)
  {
    case FieldStopMode::None:
      return "none";
    case FieldStopMode::Auto:
      return "auto";
    case FieldStopMode::File:
      return "file";
    case FieldStopMode::Circle:
      return "circle";
  }
  return "auto";
}

} // namespace vimlop
