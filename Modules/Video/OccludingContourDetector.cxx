#include <vimlop/Video/OccludingContourDetector.h>

#include <vimlop/Core/Error.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace vimlop
{

namespace
{

/// Bilinear sample of a single-channel float image; false outside it.
bool sample(const cv::Mat& image, double u, double v, double& value)
{
  if (u < 0.0 || v < 0.0 || u > image.cols - 1.0 || v > image.rows - 1.0)
  {
    return false;
  }
  const int u0 = std::min(static_cast<int>(u), image.cols - 2);
  const int v0 = std::min(static_cast<int>(v), image.rows - 2);
  const double fu = u - u0;
  const double fv = v - v0;
  const float* r0 = image.ptr<float>(v0);
  const float* r1 = image.ptr<float>(v0 + 1);
  value = (1.0 - fv) * ((1.0 - fu) * r0[u0] + fu * r0[u0 + 1]) +
    fv * ((1.0 - fu) * r1[u0] + fu * r1[u0 + 1]);
  return true;
}

void gradient(const cv::Mat& image, cv::Mat& gx, cv::Mat& gy, cv::Mat& magnitude)
{
  // Sobel with scale 1/8 is the derivative per pixel of a smooth image.
  cv::Sobel(image, gx, CV_32F, 1, 0, 3, 1.0 / 8.0, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(image, gy, CV_32F, 0, 1, 3, 1.0 / 8.0, 0.0, cv::BORDER_REPLICATE);
  cv::magnitude(gx, gy, magnitude);
}

} // namespace

OccludingContourDetector::OccludingContourDetector()
  : OccludingContourDetector(ContourDetectionOptions())
{
}

OccludingContourDetector::OccludingContourDetector(const ContourDetectionOptions& options)
  : Opts(options)
{
  if (!(options.smoothingSigmaPx > 0.0) || !(options.lowThreshold > 0.0) ||
    options.highThreshold < options.lowThreshold || !(options.logOffset > 0.0) ||
    options.minScaleRatio < 0.0 || options.spacingPx < 0.0)
  {
    throw Error("contour detector: need a positive smoothing, offset and low threshold, a high "
                "threshold at least the low one, and a non-negative scale ratio and spacing");
  }
}

std::vector<ContourPoint> OccludingContourDetector::edgePoints(const cv::Mat& frame) const
{
  const ContourDetectionOptions& o = this->Opts;
  if (frame.empty())
  {
    throw Error("contour detector: the frame is empty");
  }
  if (frame.depth() != CV_8U || (frame.channels() != 1 && frame.channels() != 3))
  {
    throw Error("contour detector: expected an 8-bit grey or BGR frame");
  }
  cv::Mat intensity;
  if (frame.channels() == 1)
  {
    frame.convertTo(intensity, CV_32F);
  }
  else if (o.channel == ContourChannel::Red)
  {
    cv::extractChannel(frame, intensity, 2);
    intensity.convertTo(intensity, CV_32F);
  }
  else
  {
    cv::Mat bgr;
    frame.convertTo(bgr, CV_32F);
    cv::transform(bgr, intensity, cv::Matx13f(0.114f, 0.587f, 0.299f));
  }
  cv::Mat logI;
  cv::log(intensity + o.logOffset, logI);

  cv::Mat smooth;
  cv::GaussianBlur(
    logI, smooth, cv::Size(0, 0), o.smoothingSigmaPx, o.smoothingSigmaPx, cv::BORDER_REPLICATE);
  cv::Mat gx;
  cv::Mat gy;
  cv::Mat magnitude;
  gradient(smooth, gx, gy, magnitude);
  // The scale test compares with the gradient at twice the smoothing; an
  // edge moves by a pixel or so between scales, so take the strongest coarse
  // gradient nearby.
  cv::Mat coarseMagnitude;
  if (o.minScaleRatio > 0.0)
  {
    cv::Mat coarse;
    cv::GaussianBlur(logI, coarse, cv::Size(0, 0), 2.0 * o.smoothingSigmaPx,
      2.0 * o.smoothingSigmaPx, cv::BORDER_REPLICATE);
    cv::Mat cx;
    cv::Mat cy;
    gradient(coarse, cx, cy, coarseMagnitude);
    cv::dilate(coarseMagnitude, coarseMagnitude, cv::Mat::ones(3, 3, CV_8U));
  }
  const int w = frame.cols;
  const int h = frame.rows;
  const int border = std::max(1, o.borderPx);
  // Non-maximum suppression along the gradient: 0 none, 1 weak, 2 strong.
  cv::Mat_<unsigned char> kind = cv::Mat_<unsigned char>::zeros(h, w);
  for (int v = border; v < h - border; ++v)
  {
    const float* m = magnitude.ptr<float>(v);
    const float* dx = gx.ptr<float>(v);
    const float* dy = gy.ptr<float>(v);
    for (int u = border; u < w - border; ++u)
    {
      if (m[u] < o.lowThreshold)
      {
        continue;
      }
      const double nx = dx[u] / m[u];
      const double ny = dy[u] / m[u];
      double before = 0.0;
      double after = 0.0;
      sample(magnitude, u - nx, v - ny, before);
      sample(magnitude, u + nx, v + ny, after);
      // Ties go to one side only, so a plateau gives a one-pixel line.
      if (m[u] > before && m[u] >= after)
      {
        kind(v, u) = m[u] >= o.highThreshold ? 2 : 1;
      }
    }
  }

  // Hysteresis, then the scale and dark-side tests per pixel.
  cv::Mat_<unsigned char> edge = cv::Mat_<unsigned char>::zeros(h, w);
  std::vector<cv::Point> stack;
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      if (kind(v, u) == 2 && !edge(v, u))
      {
        edge(v, u) = 1;
        stack.emplace_back(u, v);
        while (!stack.empty())
        {
          const cv::Point p = stack.back();
          stack.pop_back();
          for (int dv = -1; dv <= 1; ++dv)
          {
            for (int du = -1; du <= 1; ++du)
            {
              const int uu = p.x + du;
              const int vv = p.y + dv;
              if (uu >= 0 && vv >= 0 && uu < w && vv < h && kind(vv, uu) && !edge(vv, uu))
              {
                edge(vv, uu) = 1;
                stack.emplace_back(uu, vv);
              }
            }
          }
        }
      }
    }
  }
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      if (!edge(v, u))
      {
        continue;
      }
      const float m = magnitude.at<float>(v, u);
      const double nx = -gx.at<float>(v, u) / m;
      const double ny = -gy.at<float>(v, u) / m;
      bool keep = o.minScaleRatio <= 0.0 || m >= o.minScaleRatio * coarseMagnitude.at<float>(v, u);
      for (size_t k = 0; keep && k < o.darkSideProbesPx.size(); ++k)
      {
        const double a = o.darkSideProbesPx[k];
        double nearSide = 0.0;
        double farSide = 0.0;
        keep = sample(smooth, u - a * nx, v - a * ny, nearSide) &&
          sample(smooth, u + a * nx, v + a * ny, farSide) &&
          nearSide - farSide >= o.darkSideMinLogStep;
      }
      edge(v, u) = keep ? 1 : 0;
    }
  }

  // Chains: 8-connected components of the surviving pixels.
  cv::Mat_<int> labels;
  const int components = cv::connectedComponents(edge, labels, 8, CV_32S);
  std::vector<int> sizes(static_cast<size_t>(components), 0);
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      ++sizes[static_cast<size_t>(labels(v, u))];
    }
  }
  struct Candidate
  {
    ContourPoint point;
    float strength;
  };
  std::vector<Candidate> candidates;
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      if (!edge(v, u) || sizes[static_cast<size_t>(labels(v, u))] < o.minChainLengthPx)
      {
        continue;
      }
      const float m = magnitude.at<float>(v, u);
      const double dx = gx.at<float>(v, u) / m;
      const double dy = gy.at<float>(v, u) / m;
      // Sub-pixel position: the vertex of the parabola through the gradient
      // magnitudes one pixel before, at and after the pixel along the gradient.
      double before = m;
      double after = m;
      sample(magnitude, u - dx, v - dy, before);
      sample(magnitude, u + dx, v + dy, after);
      const double curvature = before - 2.0 * m + after;
      double offset = curvature < 0.0 ? 0.5 * (before - after) / curvature : 0.0;
      offset = std::clamp(offset, -0.5, 0.5);
      Candidate c;
      c.point.pixel = Eigen::Vector2d(u + offset * dx, v + offset * dy);
      c.point.normal = Eigen::Vector2d(-dx, -dy).normalized();
      c.strength = m;
      candidates.push_back(c);
    }
  }
  // Strongest first: thinning keeps the best-localised points.
  std::stable_sort(candidates.begin(), candidates.end(),
    [](const Candidate& a, const Candidate& b) { return a.strength > b.strength; });
  std::vector<ContourPoint> points;
  points.reserve(candidates.size());
  for (const Candidate& c : candidates)
  {
    points.push_back(c.point);
  }
  return points;
}

std::vector<ContourPoint> OccludingContourDetector::detect(const cv::Mat& frame) const
{
  return thin(this->edgePoints(frame), this->Opts.spacingPx);
}

std::vector<ContourPoint> OccludingContourDetector::detect(
  const cv::Mat& frame, const cv::Mat& validMask, MaskedDetectionCounts* counts) const
{
  if (validMask.empty())
  {
    std::vector<ContourPoint> all = this->detect(frame);
    if (counts)
    {
      counts->detected = all.size();
      counts->dropped = 0;
    }
    return all;
  }
  if (validMask.type() != CV_8U || validMask.cols != frame.cols || validMask.rows != frame.rows)
  {
    throw Error(
      "contour detector: the mask must be an 8-bit single-channel image of the frame's size");
  }
  const std::vector<ContourPoint> points = this->edgePoints(frame);
  auto inside = [&validMask](const ContourPoint& p)
  {
    const int u = static_cast<int>(std::lround(p.pixel.x()));
    const int v = static_cast<int>(std::lround(p.pixel.y()));
    return u >= 0 && v >= 0 && u < validMask.cols && v < validMask.rows &&
      validMask.at<unsigned char>(v, u) != 0;
  };
  // Masked before thinning, so that a point on the field stop's edge does
  // not push out a real contour point near it.
  std::vector<ContourPoint> kept;
  kept.reserve(points.size());
  for (const ContourPoint& p : points)
  {
    if (inside(p))
    {
      kept.push_back(p);
    }
  }
  kept = thin(kept, this->Opts.spacingPx);
  if (counts)
  {
    // What the detector would have returned without the mask, and how many
    // of those the mask removes.
    const std::vector<ContourPoint> all = thin(points, this->Opts.spacingPx);
    counts->detected = all.size();
    counts->dropped = static_cast<size_t>(std::count_if(
      all.begin(), all.end(), [&inside](const ContourPoint& p) { return !inside(p); }));
  }
  return kept;
}

std::vector<ContourPoint> OccludingContourDetector::thin(
  const std::vector<ContourPoint>& points, double spacingPx)
{
  if (!(spacingPx > 0.0))
  {
    return points;
  }
  // A point is skipped when one kept before it lies closer than the spacing;
  // a grid of spacing-sized cells finds the neighbours.
  const double spacing2 = spacingPx * spacingPx;
  std::unordered_map<long long, std::vector<Eigen::Vector2d>> grid;
  auto key = [](long long i, long long j) { return i * 1000003LL + j; };
  std::vector<ContourPoint> kept;
  for (const ContourPoint& c : points)
  {
    const long long i = static_cast<long long>(std::floor(c.pixel.x() / spacingPx));
    const long long j = static_cast<long long>(std::floor(c.pixel.y() / spacingPx));
    bool near = false;
    for (long long di = -1; di <= 1 && !near; ++di)
    {
      for (long long dj = -1; dj <= 1 && !near; ++dj)
      {
        const auto found = grid.find(key(i + di, j + dj));
        if (found == grid.end())
        {
          continue;
        }
        for (const Eigen::Vector2d& q : found->second)
        {
          if ((q - c.pixel).squaredNorm() < spacing2)
          {
            near = true;
            break;
          }
        }
      }
    }
    if (!near)
    {
      grid[key(i, j)].push_back(c.pixel);
      kept.push_back(c);
    }
  }
  return kept;
}

} // namespace vimlop
