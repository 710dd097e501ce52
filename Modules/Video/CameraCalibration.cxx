#include <vimlop/Video/CameraCalibration.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>

namespace vimlop
{

namespace
{

/// The dictionaries OpenCV predefines, by their names without DICT_.
cv::Ptr<cv::aruco::Dictionary> dictionaryNamed(const std::string& name)
{
  static const std::vector<std::pair<std::string, cv::aruco::PREDEFINED_DICTIONARY_NAME>> known = {
    { "4X4_50", cv::aruco::DICT_4X4_50 }, { "4X4_100", cv::aruco::DICT_4X4_100 },
    { "4X4_250", cv::aruco::DICT_4X4_250 }, { "4X4_1000", cv::aruco::DICT_4X4_1000 },
    { "5X5_50", cv::aruco::DICT_5X5_50 }, { "5X5_100", cv::aruco::DICT_5X5_100 },
    { "5X5_250", cv::aruco::DICT_5X5_250 }, { "5X5_1000", cv::aruco::DICT_5X5_1000 },
    { "6X6_50", cv::aruco::DICT_6X6_50 }, { "6X6_100", cv::aruco::DICT_6X6_100 },
    { "6X6_250", cv::aruco::DICT_6X6_250 }, { "6X6_1000", cv::aruco::DICT_6X6_1000 },
    { "7X7_50", cv::aruco::DICT_7X7_50 }, { "7X7_100", cv::aruco::DICT_7X7_100 },
    { "7X7_250", cv::aruco::DICT_7X7_250 }, { "7X7_1000", cv::aruco::DICT_7X7_1000 },
    { "ARUCO_ORIGINAL", cv::aruco::DICT_ARUCO_ORIGINAL }
  };
  std::string names;
  for (const auto& [knownName, id] : known)
  {
    if (knownName == name)
    {
      return cv::aruco::getPredefinedDictionary(id);
    }
    names += (names.empty() ? "" : ", ") + knownName;
  }
  throw Error("calibration: no ArUco dictionary '" + name + "' (" + names + ")");
}

/// A view's board corners: their places on the board (mm) and in the view (px).
struct ViewCorners
{
  std::vector<cv::Point3f> board;
  std::vector<cv::Point2f> image;
};

/// Every inner corner of the chessboard, or nothing.
bool findChessboard(const cv::Mat& grey, const CameraCalibrationOptions& options,
  const std::vector<cv::Point3f>& board, ViewCorners& corners)
{
  const cv::Size pattern(options.innerCornersX, options.innerCornersY);
  if (!cv::findChessboardCorners(
        grey, pattern, corners.image, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
  {
    return false;
  }
  cv::cornerSubPix(grey, corners.image, cv::Size(5, 5), cv::Size(-1, -1),
    cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-3));
  corners.board = board;
  return true;
}

/// The corners of the ChArUco board its markers name, when there are at
/// least `minCorners`, refined to sub-pixel in a window that keeps off the
/// markers.
bool findCharuco(const cv::Mat& grey, const cv::Ptr<cv::aruco::CharucoBoard>& board, int minCorners,
  ViewCorners& corners)
{
  std::vector<std::vector<cv::Point2f>> markers;
  std::vector<int> markerIds;
  cv::aruco::detectMarkers(grey, board->dictionary, markers, markerIds);
  if (markerIds.empty())
  {
    return false;
  }
  std::vector<int> cornerIds;
  cv::aruco::interpolateCornersCharuco(markers, markerIds, grey, board, corners.image, cornerIds);
  if (static_cast<int>(cornerIds.size()) < minCorners)
  {
    return false;
  }
  // interpolateCornersCharuco's own refinement lets marker edges into its
  // window: on rendered views its corners were 0.72 px RMS from the true
  // ones, against 0.16 px for a chessboard's. A corner's saddle is clean
  // only up to the nearest marker, (square - marker) / 2 away on the board:
  // the half window is that gap in pixels, from the markers' size in this view.
  double sidePx = 0.0;
  for (const std::vector<cv::Point2f>& marker : markers)
  {
    for (size_t c = 0; c < 4; ++c)
    {
      sidePx += cv::norm(marker[c] - marker[(c + 1) % 4]) / (4.0 * markers.size());
    }
  }
  const double gapPx =
    0.5 * (board->getSquareLength() - board->getMarkerLength()) * sidePx / board->getMarkerLength();
  const int halfWindow = std::clamp(static_cast<int>(gapPx), 2, 5);
  cv::cornerSubPix(grey, corners.image, cv::Size(halfWindow, halfWindow), cv::Size(-1, -1),
    cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-3));
  for (const int id : cornerIds)
  {
    corners.board.push_back(board->chessboardCorners[static_cast<size_t>(id)]);
  }
  return true;
}

} // namespace

CameraCalibrationResult calibrateCamera(const std::vector<cv::Mat>& views,
  const std::vector<std::string>& names, const CameraCalibrationOptions& options)
{
  const bool charuco = options.pattern == CalibrationPattern::Charuco;
  if (options.innerCornersX < 2 || options.innerCornersY < 2 || !(options.squareMm > 0.0))
  {
    throw Error(formatText("calibration: a board of %dx%d inner corners and %g mm squares "
                           "cannot be found (at least 2x2 corners, squares over 0 mm)",
      options.innerCornersX, options.innerCornersY, options.squareMm));
  }
  cv::Ptr<cv::aruco::CharucoBoard> charucoBoard;
  if (charuco)
  {
    if (!(options.markerMm > 0.0 && options.markerMm < options.squareMm))
    {
      throw Error(formatText("calibration: ChArUco markers of %g mm do not fit in %g mm squares",
        options.markerMm, options.squareMm));
    }
    const cv::Ptr<cv::aruco::Dictionary> dictionary = dictionaryNamed(options.dictionary);
    // One marker in every other square.
    const int markers = ((options.innerCornersX + 1) * (options.innerCornersY + 1)) / 2;
    if (markers > dictionary->bytesList.rows)
    {
      throw Error(formatText("calibration: a %dx%d ChArUco board has %d markers; the dictionary "
                             "%s has only %d",
        options.innerCornersX + 1, options.innerCornersY + 1, markers, options.dictionary.c_str(),
        dictionary->bytesList.rows));
    }
    charucoBoard =
      cv::aruco::CharucoBoard::create(options.innerCornersX + 1, options.innerCornersY + 1,
        static_cast<float>(options.squareMm), static_cast<float>(options.markerMm), dictionary);
  }
  std::vector<cv::Point3f> board;
  for (int y = 0; y < options.innerCornersY; ++y)
  {
    for (int x = 0; x < options.innerCornersX; ++x)
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
    ViewCorners corners;
    if (!(charuco ? findCharuco(grey, charucoBoard, options.minCornersPerView, corners)
                  : findChessboard(grey, options, board, corners)))
    {
      result.viewsWithoutBoard.push_back(name);
      continue;
    }
    result.cornersUsed += static_cast<int>(corners.image.size());
    objectPoints.push_back(std::move(corners.board));
    imagePoints.push_back(std::move(corners.image));
    result.viewsUsed.push_back(name);
  }
  if (static_cast<int>(result.viewsUsed.size()) < options.minViews)
  {
    throw Error(charuco
        ? formatText("calibration: %zu of %zu views show at least %d corners of the %dx%d "
                     "ChArUco board (inner corners, dictionary %s); at least %d are needed",
            result.viewsUsed.size(), views.size(), options.minCornersPerView, options.innerCornersX,
            options.innerCornersY, options.dictionary.c_str(), options.minViews)
        : formatText("calibration: %zu of %zu views show the whole %dx%d board (inner "
                     "corners); at least %d are needed",
            result.viewsUsed.size(), views.size(), options.innerCornersX, options.innerCornersY,
            options.minViews));
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
