#include <vimlop/Evaluation/LensDistortionRendering.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace vimlop
{

namespace
{

constexpr float noSource = -1e6f;

cv::Mat cameraMatrix(const PinholeCamera& k)
{
  return (cv::Mat_<double>(3, 3) << k.fx, 0.0, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0);
}

cv::Mat coefficients(const PinholeCamera& k)
{
  cv::Mat d(1, static_cast<int>(k.distortion.size()), CV_64F);
  for (int i = 0; i < d.cols; ++i)
  {
    d.at<double>(0, i) = k.distortion[i];
  }
  return d;
}

/// True while the distorted radius still grows with the undistorted one:
/// past the first radius where it stops, barrel distortion folds the picture
/// back and a distorted pixel has two sources. For the radial-tangential
/// model, r (1 + k1 r^2 + k2 r^4 + k3 r^6) in the normalized radius r (r2 =
/// r^2); for the fisheye, theta_d(theta) in the ray's angle theta = atan(r).
bool beforeTheFold(const PinholeCamera& k, double r2)
{
  auto coefficient = [&](Eigen::Index i)
  { return i < k.distortion.size() ? k.distortion[i] : 0.0; };
  if (k.lensModel == LensModel::Fisheye)
  {
    const double theta = std::atan(std::sqrt(r2));
    const double t2 = theta * theta;
    return 1.0 +
      t2 *
        (3.0 * coefficient(0) +
          t2 * (5.0 * coefficient(1) + t2 * (7.0 * coefficient(2) + t2 * 9.0 * coefficient(3)))) >
      0.0;
  }
  const double k1 = coefficient(0);
  const double k2 = coefficient(1);
  const double k3 = coefficient(4);
  return 1.0 + 3.0 * k1 * r2 + 5.0 * k2 * r2 * r2 + 7.0 * k3 * r2 * r2 * r2 > 0.0;
}

/// The normalized pinhole coordinates (x/z, y/z) of the rays of `pixels`
/// through the lens of `k`, and the pixels those rays project back to, both
/// with OpenCV's functions of the lens's model.
void undistortAndProjectBack(const PinholeCamera& k, const std::vector<cv::Point2d>& pixels,
  std::vector<cv::Point2d>& normalized, std::vector<cv::Point2d>& back)
{
  const cv::Mat matrix = cameraMatrix(k);
  const cv::Mat d = coefficients(k);
  // OpenCV's default 5 (10 for the fisheye) iterations are far from
  // converged for the k1 of wide-angle endoscopes; the round trip checks
  // what they give.
  const cv::TermCriteria converged(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-10);
  if (k.lensModel == LensModel::Fisheye)
  {
    cv::fisheye::undistortPoints(
      pixels, normalized, matrix, d, cv::noArray(), cv::noArray(), converged);
  }
  else
  {
    cv::undistortPoints(pixels, normalized, matrix, d, cv::noArray(), cv::noArray(), converged);
  }
  std::vector<cv::Point3d> rays;
  rays.reserve(normalized.size());
  for (const cv::Point2d& n : normalized)
  {
    rays.emplace_back(n.x, n.y, 1.0);
  }
  if (k.lensModel == LensModel::Fisheye)
  {
    cv::fisheye::projectPoints(rays, back, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), matrix, d);
  }
  else
  {
    cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), matrix, d, back);
  }
}

/// Pinhole pixels of every distorted pixel, row by row; NaN where there is none.
std::vector<cv::Point2d> undistortedPixels(
  const PinholeCamera& distorted, const PinholeCamera& pinhole)
{
  const int w = distorted.widthPx;
  const int h = distorted.heightPx;
  std::vector<cv::Point2d> pixels;
  pixels.reserve(static_cast<size_t>(w) * h);
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      pixels.emplace_back(u, v);
    }
  }
  if (!distorted.hasDistortion())
  {
    for (cv::Point2d& p : pixels)
    {
      p = cv::Point2d(pinhole.fx * (p.x - distorted.cx) / distorted.fx + pinhole.cx,
        pinhole.fy * (p.y - distorted.cy) / distorted.fy + pinhole.cy);
    }
    return pixels;
  }
  std::vector<cv::Point2d> normalized;
  std::vector<cv::Point2d> back;
  undistortAndProjectBack(distorted, pixels, normalized, back);
  for (size_t i = 0; i < pixels.size(); ++i)
  {
    const cv::Point2d& n = normalized[i];
    const bool valid = std::isfinite(n.x) && std::isfinite(n.y) &&
      beforeTheFold(distorted, n.x * n.x + n.y * n.y) && cv::norm(back[i] - pixels[i]) < 0.01;
    pixels[i] = valid ? cv::Point2d(pinhole.fx * n.x + pinhole.cx, pinhole.fy * n.y + pinhole.cy)
                      : cv::Point2d(std::nan(""), std::nan(""));
  }
  return pixels;
}

} // namespace

cv::Mat distortedToPinholeMap(
  const PinholeCamera& distortedCamera, const PinholeCamera& pinholeCamera)
{
  const std::vector<cv::Point2d> pixels = undistortedPixels(distortedCamera, pinholeCamera);
  cv::Mat map(distortedCamera.heightPx, distortedCamera.widthPx, CV_32FC2);
  for (int v = 0; v < map.rows; ++v)
  {
    for (int u = 0; u < map.cols; ++u)
    {
      const cv::Point2d& p = pixels[static_cast<size_t>(v) * map.cols + u];
      map.at<cv::Vec2f>(v, u) = std::isfinite(p.x)
        ? cv::Vec2f(static_cast<float>(p.x), static_cast<float>(p.y))
        : cv::Vec2f(noSource, noSource);
    }
  }
  return map;
}

PinholeCamera pinholeCameraCovering(const PinholeCamera& distortedCamera)
{
  PinholeCamera pinhole = distortedCamera;
  pinhole.removeDistortion();
  double minU = 0.0;
  double minV = 0.0;
  double maxU = distortedCamera.widthPx - 1.0;
  double maxV = distortedCamera.heightPx - 1.0;
  for (const cv::Point2d& p : undistortedPixels(distortedCamera, pinhole))
  {
    if (std::isfinite(p.x))
    {
      minU = std::min(minU, p.x);
      maxU = std::max(maxU, p.x);
      minV = std::min(minV, p.y);
      maxV = std::max(maxV, p.y);
    }
  }
  // Whole-pixel shifts keep the pixel centres of both pictures on one grid.
  const double limitU = 1.5 * distortedCamera.widthPx;
  const double limitV = 1.5 * distortedCamera.heightPx;
  const int left = static_cast<int>(std::ceil(std::min(-minU, limitU))) + 1;
  const int top = static_cast<int>(std::ceil(std::min(-minV, limitV))) + 1;
  const int right =
    static_cast<int>(std::ceil(std::min(maxU - (distortedCamera.widthPx - 1.0), limitU))) + 1;
  const int bottom =
    static_cast<int>(std::ceil(std::min(maxV - (distortedCamera.heightPx - 1.0), limitV))) + 1;
  pinhole.cx += left;
  pinhole.cy += top;
  pinhole.widthPx += left + right;
  pinhole.heightPx += top + bottom;
  return pinhole;
}

cv::Mat renderLensDistortion(const cv::Mat& pinholePicture, const cv::Mat& map)
{
  cv::Mat distorted;
  cv::remap(pinholePicture, distorted, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
    cv::Scalar::all(0));
  return distorted;
}

DepthMap renderLensDistortion(const DepthMap& pinholeDepth, const cv::Mat& map)
{
  DepthMap depth;
  depth.widthPx = map.cols;
  depth.heightPx = map.rows;
  depth.depthMm.assign(static_cast<size_t>(map.cols) * map.rows, DepthMap::noSurface());
  for (int v = 0; v < map.rows; ++v)
  {
    for (int u = 0; u < map.cols; ++u)
    {
      const cv::Vec2f p = map.at<cv::Vec2f>(v, u);
      const long su = std::lround(p[0]);
      const long sv = std::lround(p[1]);
      if (su >= 0 && sv >= 0 && su < pinholeDepth.widthPx && sv < pinholeDepth.heightPx)
      {
        depth.depthMm[static_cast<size_t>(v) * map.cols + u] =
          pinholeDepth.at(static_cast<int>(su), static_cast<int>(sv));
      }
    }
  }
  return depth;
}

} // namespace vimlop
