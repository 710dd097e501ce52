#ifndef vimlop_BoardViews_h
#define vimlop_BoardViews_h

// Rendered views of a chessboard or a ChArUco board through a known lens,
// for the calibration tests (TestCameraCalibration.cxx and, written to files
// by VIMLOPWriteBoardViews, the `vimlop calibrate` tests).

#include <vimlop/Core/PinholeCamera.h>

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <cmath>
#include <functional>
#include <vector>

namespace vimlop::fixtures
{

constexpr int widthPx = 480;
constexpr int heightPx = 360;
constexpr double squareMm = 5.0;

inline cv::Mat cameraMatrix(const PinholeCamera& k)
{
  return (cv::Mat_<double>(3, 3) << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
}

inline cv::Mat coefficients(const PinholeCamera& k)
{
  cv::Mat d(1, static_cast<int>(k.distortion.size()), CV_64F);
  for (int i = 0; i < d.cols; ++i)
  {
    d.at<double>(0, i) = k.distortion[i];
  }
  return d;
}

/// The normalised pinhole coordinates of the rays of `pixels`, through the lens of `k`.
inline std::vector<cv::Point2d> raysOf(
  const PinholeCamera& k, const std::vector<cv::Point2d>& pixels)
{
  std::vector<cv::Point2d> rays;
  if (k.lensModel == LensModel::Fisheye)
  {
    cv::fisheye::undistortPoints(pixels, rays, cameraMatrix(k), coefficients(k));
  }
  else
  {
    cv::undistortPoints(pixels, rays, cameraMatrix(k), coefficients(k), cv::noArray(),
      cv::noArray(), cv::TermCriteria(cv::TermCriteria::COUNT, 50, 0));
  }
  return rays;
}

/// What a board shows at (x, y) mm in its plane, the first inner corner at
/// the origin: a grey level (20 black, 235 white, 128 the grey around it).
using BoardPattern = std::function<double(double x, double y)>;

/// A 9 x 6 (inner corners) chessboard with a white margin of one square.
inline double chessboardAt(double x, double y)
{
  const int ix = static_cast<int>(std::floor(x / squareMm)) + 1;
  const int iy = static_cast<int>(std::floor(y / squareMm)) + 1;
  if (ix < -1 || ix > 11 || iy < -1 || iy > 8)
  {
    return 128.0;
  }
  const bool square = ix >= 0 && ix <= 9 && iy >= 0 && iy <= 6;
  return square && (ix + iy) % 2 == 0 ? 20.0 : 235.0;
}

/// The same board as a ChArUco board (10 x 7 squares, 3.5 mm markers of
/// DICT_4X4_50), as OpenCV draws it, with the same white margin.
inline BoardPattern charucoBoard()
{
  constexpr int pxPerSquare = 60;
  const cv::Ptr<cv::aruco::CharucoBoard> board = cv::aruco::CharucoBoard::create(
    10, 7, 5.0f, 3.5f, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50));
  cv::Mat picture;
  board->draw(cv::Size(10 * pxPerSquare, 7 * pxPerSquare), picture, 0, 1);
  return [picture](double x, double y)
  {
    // The board's outer corner is one square before the first inner corner.
    const double u = (x / squareMm + 1.0) * pxPerSquare;
    const double v = (y / squareMm + 1.0) * pxPerSquare;
    if (u < -pxPerSquare || v < -pxPerSquare || u >= 11 * pxPerSquare || v >= 8 * pxPerSquare)
    {
      return 128.0;
    }
    if (u < 0.0 || v < 0.0 || u >= picture.cols || v >= picture.rows)
    {
      return 235.0;
    }
    const double value = picture.at<unsigned char>(static_cast<int>(v), static_cast<int>(u));
    return 20.0 + (235.0 - 20.0) * value / 255.0;
  };
}

/**
 * The board `pattern` on grey, seen by camera `k` from the board pose
 * (rotation vector, translation in mm; board x, y in its plane): each pixel
 * averages 2 x 2 rays traced through the lens to the board's plane.
 */
inline cv::Mat renderBoard(const PinholeCamera& k, const cv::Vec3d& rotationVector,
  const cv::Vec3d& t, const BoardPattern& pattern = chessboardAt)
{
  cv::Matx33d r;
  cv::Rodrigues(rotationVector, r);
  const cv::Matx33d rt = r.t();
  std::vector<cv::Point2d> pixels;
  for (int v = 0; v < heightPx; ++v)
  {
    for (int u = 0; u < widthPx; ++u)
    {
      for (double du : { -0.25, 0.25 })
      {
        for (double dv : { -0.25, 0.25 })
        {
          pixels.emplace_back(u + du, v + dv);
        }
      }
    }
  }
  const std::vector<cv::Point2d> rays = raysOf(k, pixels);
  const cv::Vec3d tBoard = rt * t;
  cv::Mat view(heightPx, widthPx, CV_8UC1);
  for (int p = 0; p < widthPx * heightPx; ++p)
  {
    double sum = 0.0;
    for (int s = 0; s < 4; ++s)
    {
      const cv::Point2d& ray = rays[static_cast<size_t>(4 * p + s)];
      const cv::Vec3d d = rt * cv::Vec3d(ray.x, ray.y, 1.0);
      const double depth = tBoard[2] / d[2];
      sum += depth > 0.0 ? pattern(depth * d[0] - tBoard[0], depth * d[1] - tBoard[1]) : 128.0;
    }
    view.at<unsigned char>(p / widthPx, p % widthPx) = static_cast<unsigned char>(sum / 4.0);
  }
  return view;
}

/// Twelve views of the board 60-70 mm away, turned 20 degrees, its centre
/// moved over the image so that its corners reach most of the field: a
/// calibration only knows the lens where it saw corners. `spread` scales
/// the moves: at 1.6 the board leaves the image in the outer views, as it
/// does in an endoscope's small field.
inline std::vector<cv::Mat> boardViews(
  const PinholeCamera& k, const BoardPattern& pattern = chessboardAt, double spread = 1.0)
{
  std::vector<cv::Mat> views;
  int n = 0;
  for (double offsetY : { -16.0 * spread, 0.0, 16.0 * spread })
  {
    for (double offsetX : { -24.0 * spread, -8.0 * spread, 8.0 * spread, 24.0 * spread })
    {
      // Turned 20 degrees about both of its axes, the signs alternating: tilt
      // is what tells the focal length from the distance.
      const cv::Vec3d turn(n % 2 ? 0.35 : -0.35, (n / 2) % 2 ? 0.35 : -0.35, 0.1 * (n % 3 - 1));
      // The board's centre (22.5, 12.5 mm from its first corner) at the offset.
      const cv::Vec3d centre(offsetX, offsetY, 60.0 + 2.5 * (n % 5));
      cv::Matx33d r;
      cv::Rodrigues(turn, r);
      views.push_back(renderBoard(k, turn, centre - r * cv::Vec3d(22.5, 12.5, 0.0), pattern));
      ++n;
    }
  }
  return views;
}

/// The lens the views are rendered through: a barrel lens (OpenCV's model) or a fisheye.
inline PinholeCamera trueCamera(LensModel model)
{
  PinholeCamera k;
  k.widthPx = widthPx;
  k.heightPx = heightPx;
  k.fx = 310.0;
  k.fy = 306.0;
  k.cx = 243.0;
  k.cy = 176.5;
  k.lensModel = model;
  k.distortion.resize(4);
  if (model == LensModel::Fisheye)
  {
    k.distortion << 0.03, -0.01, 0.002, -0.0005;
  }
  else
  {
    // Barrel distortion that stays monotonic over the whole image (a
    // stronger one folds near the corners, where a rendered board is then wrong).
    k.distortion << -0.12, 0.02, 0.001, -0.0005;
  }
  return k;
}

} // namespace vimlop::fixtures

#endif
