#include <vimlop/Video/CameraCalibration.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace vimlop
{

CameraCalibrationResult calibrateCamera(const std::vector<cv::Mat>& views,
  const std::vector<std::string>& names, const CameraCalibrationOptions& options)
{
  if (options.innerCornersX < 2 || options.innerCornersY < 2 || !(options.squareMm > 0.0))
  {
    throw Error(formatText("calibration: a board of %dx%d inner corners and %g mm squares "
                           "cannot be found (at least 2x2 corners, squares over 0 mm)",
      options.innerCornersX, options.innerCornersY, options.squareMm));
  }
  const cv::Size pattern(options.innerCornersX, options.innerCornersY);
  std::vector<cv::Point3f> board;
  for (int y = 0; y < pattern.height; ++y)
  {
    for (int x = 0; x < pattern.width; ++x)
    {
      board.emplace_back(
        static_cast<float>(x * options.squareMm), static_cast<float>(y * options.squareMm), 0.0f);
    }
  }
  CameraCalibrationResult result;
  std::vector<std::vector<cv::Point3f>> objectPoints;
  std::vector<std::vector<cv::Point2f>> imagePoints;
  cv::Size size;
  for (size_t v = 0; v < views.size(); ++v)
  {
    const std::string& name = v < names.size() ? names[v] : std::to_string(v);
    if (size.empty())
    {
      size = views[v].size();
    }
    else if (views[v].size() != size)
    {
      throw Error(formatText("calibration: view '%s' is %dx%d, the first %dx%d", name.c_str(),
        views[v].cols, views[v].rows, size.width, size.height));
    }
    cv::Mat grey;
    if (views[v].channels() == 1)
    {
      grey = views[v];
    }
    else
    {
      cv::cvtColor(views[v], grey, cv::COLOR_BGR2GRAY);
    }
    std::vector<cv::Point2f> corners;
    if (!cv::findChessboardCorners(
          grey, pattern, corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
    {
      result.viewsWithoutBoard.push_back(name);
      continue;
    }
    cv::cornerSubPix(grey, corners, cv::Size(5, 5), cv::Size(-1, -1),
      cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-3));
    objectPoints.push_back(board);
    imagePoints.push_back(corners);
    result.viewsUsed.push_back(name);
  }
  if (static_cast<int>(result.viewsUsed.size()) < options.minViews)
  {
    throw Error(formatText("calibration: %zu of %zu views show the whole %dx%d board (inner "
                           "corners); at least %d are needed",
      result.viewsUsed.size(), views.size(), pattern.width, pattern.height, options.minViews));
  }
  cv::Mat k;
  cv::Mat distortion;
  std::vector<cv::Mat> rotations;
  std::vector<cv::Mat> translations;
  try
  {
    if (options.lensModel == LensModel::Fisheye)
    {
      std::vector<std::vector<cv::Point3d>> objects(objectPoints.size());
      std::vector<std::vector<cv::Point2d>> images(imagePoints.size());
      for (size_t v = 0; v < objectPoints.size(); ++v)
      {
        objects[v].assign(objectPoints[v].begin(), objectPoints[v].end());
        images[v].assign(imagePoints[v].begin(), imagePoints[v].end());
      }
      result.rmsReprojectionErrorPx =
        cv::fisheye::calibrate(objects, images, size, k, distortion, rotations, translations,
          cv::fisheye::CALIB_RECOMPUTE_EXTRINSIC | cv::fisheye::CALIB_FIX_SKEW,
          cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-10));
    }
    else
    {
      result.rmsReprojectionErrorPx = cv::calibrateCamera(
        objectPoints, imagePoints, size, k, distortion, rotations, translations, cv::CALIB_FIX_K3);
    }
  }
  catch (const cv::Exception& e)
  {
    throw Error(std::string("calibration: the fit failed (") + e.what() + ")");
  }
  PinholeCamera& camera = result.intrinsics;
  camera.widthPx = size.width;
  camera.heightPx = size.height;
  camera.fx = k.at<double>(0, 0);
  camera.fy = k.at<double>(1, 1);
  camera.cx = k.at<double>(0, 2);
  camera.cy = k.at<double>(1, 2);
  camera.lensModel = options.lensModel;
  const cv::Mat coefficients = distortion.reshape(1, 1);
  // Four coefficients either way: the fisheye's k1..k4, or k1, k2, p1, p2 (the
  // radial-tangential fit returns k3 too, held at 0).
  const int count = 4;
  camera.distortion.resize(count);
  for (int i = 0; i < count; ++i)
  {
    camera.distortion[i] = coefficients.at<double>(0, i);
  }
  return result;
}

} // namespace vimlop
