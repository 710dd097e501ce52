#ifndef vimlop_CameraCalibration_h
#define vimlop_CameraCalibration_h

#include <vimlop/Core/LensModel.h>
#include <vimlop/Core/PinholeCamera.h>

#include <opencv2/core/mat.hpp>

#include <string>
#include <vector>

namespace vimlop
{

/// @brief The kind of calibration board.
enum class CalibrationPattern
{
  /// Black and white squares: every inner corner must be seen in a view.
  Chessboard,
  /// A ChArUco board (OpenCV's aruco): a chessboard whose white squares hold
  /// ArUco markers, which name the corners, so a view that shows part of the
  /// board still counts (an endoscope's small field rarely shows all of it).
  Charuco
};

/// @brief A calibration target and the lens model to fit.
struct CameraCalibrationOptions
{
  CalibrationPattern pattern = CalibrationPattern::Chessboard;
  /// Inner corners along the board's rows and columns (default 9 x 6, OpenCV's
  /// sample board); a ChArUco board has one square more each way (10 x 7).
  int innerCornersX = 9;
  int innerCornersY = 6;
  /// Side of one square, mm (default 5: a board for an endoscope's working distance).
  double squareMm = 5.0;
  /// ChArUco: side of a marker, mm (default 3.5, 70 % of the square, as
  /// OpenCV's sample boards), and the ArUco dictionary the markers come from
  /// (OpenCV's name without DICT_, e.g. 4X4_50, 5X5_100, 6X6_250).
  double markerMm = 3.5;
  std::string dictionary = "4X4_50";
  /// ChArUco: least corners a view must show to be used (default 12: a
  /// homography with room to spare; fewer corners say little of the lens).
  int minCornersPerView = 12;
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
  /// The views used (those that show the whole board, or for ChArUco at
  /// least `minCornersPerView` of its corners), by name.
  std::vector<std::string> viewsUsed;
  /// The views in which the board was not found (enough of it), by name.
  std::vector<std::string> viewsWithoutBoard;
  /// The board corners used, over all views.
  int cornersUsed = 0;
};

/**
 * @brief Calibrates a camera from views of a chessboard (OpenCV's
 * findChessboardCorners refined by cornerSubPix) or of a ChArUco board
 * (aruco's detectMarkers and interpolateCornersCharuco), then
 * calibrateCamera, or cv::fisheye::calibrate for the fisheye model. `names`
 * name the views in the result and in messages. Pixels follow
 * PinholeCamera's convention (OpenCV's).
 * @throws vimlop::Error when the views differ in size, fewer than
 * `minViews` show the board, the board or dictionary cannot be made, or the
 * fit fails.
 */
CameraCalibrationResult calibrateCamera(const std::vector<cv::Mat>& views,
  const std::vector<std::string>& names, const CameraCalibrationOptions& options);

} // namespace vimlop

#endif
