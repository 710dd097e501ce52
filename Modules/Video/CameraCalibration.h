#ifndef vimlop_CameraCalibration_h
#define vimlop_CameraCalibration_h

#include <vimlop/Core/LensModel.h>
#include <vimlop/Core/PinholeCamera.h>

#include <opencv2/core/mat.hpp>

#include <string>
#include <vector>

namespace vimlop
{

/// @brief A chessboard calibration target and the lens model to fit.
struct CameraCalibrationOptions
{
  /// Inner corners along the board's rows and columns (default 9 x 6, OpenCV's sample board).
  int innerCornersX = 9;
  int innerCornersY = 6;
  /// Side of one square, mm (default 5: a board for an endoscope's working distance).
  double squareMm = 5.0;
  /// RadialTangential (OpenCV's default model; k1, k2, p1, p2 fitted, k3
  /// held at 0, which few views of a small board cannot pin down) or Fisheye (k1..k4).
  LensModel lensModel = LensModel::RadialTangential;
  /// Least views that show the whole board (default 5).
  int minViews = 5;
};

/// @brief What a calibration found.
struct CameraCalibrationResult
{
  PinholeCamera intrinsics;
  /// Root mean square distance between detected and reprojected corners, px.
  double rmsReprojectionErrorPx = 0.0;
  /// The views used (those that show the whole board), by name.
  std::vector<std::string> viewsUsed;
  /// The views in which the board was not found, by name.
  std::vector<std::string> viewsWithoutBoard;
};

/**
 * @brief Calibrates a camera from views of a chessboard (OpenCV's
 * findChessboardCorners refined by cornerSubPix, then calibrateCamera, or
 * cv::fisheye::calibrate for the fisheye model). `names` name the views in
 * the result and in messages. Pixels follow PinholeCamera's convention
 * (OpenCV's).
 * @throws vimlop::Error when the views differ in size, fewer than
 * `minViews` show the whole board, or the fit fails.
 */
CameraCalibrationResult calibrateCamera(const std::vector<cv::Mat>& views,
  const std::vector<std::string>& names, const CameraCalibrationOptions& options);

} // namespace vimlop

#endif
