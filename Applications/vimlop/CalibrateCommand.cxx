#include "CommandLine.h"
#include "Commands.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Video/CameraCalibration.h>
#include <vimlop/Video/FrameSequence.h>
#include <vimlop/Video/IntrinsicsIO.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

namespace vimlop
{

namespace
{

struct CalibrateOptions
{
  std::string frames;
  std::string out;
  std::string board = "9x6";
  std::string pattern = "chessboard";
  bool fisheye = false;
  bool json = false;
  CameraCalibrationOptions calibration;
};

void runCalibrate(CalibrateOptions o)
{
  int x = 0;
  int y = 0;
  char end = 0;
  if (std::sscanf(o.board.c_str(), "%dx%d%c", &x, &y, &end) != 2)
  {
    throw Error(
      "--board: expected the inner corners as COLUMNSxROWS (e.g. 9x6), got '" + o.board + "'");
  }
  o.calibration.innerCornersX = x;
  o.calibration.innerCornersY = y;
  o.calibration.lensModel = o.fisheye ? LensModel::Fisheye : LensModel::RadialTangential;
  o.calibration.pattern =
    o.pattern == "charuco" ? CalibrationPattern::Charuco : CalibrationPattern::Chessboard;
  if (!isIntrinsicsPath(o.out))
  {
    throw Error("--out: '" + o.out + "' is not an intrinsics file name (.yaml, .yml, .json, .xml)");
  }
  const FrameSequence views = FrameSequence::load(o.frames);
  std::vector<cv::Mat> pictures;
  for (int v = 0; v < views.size(); ++v)
  {
    pictures.push_back(views.frame(v));
  }
  const CameraCalibrationResult fit = calibrateCamera(pictures, views.names(), o.calibration);
  const bool charuco = o.calibration.pattern == CalibrationPattern::Charuco;
  if (!fit.viewsWithoutBoard.empty())
  {
    std::cerr << "vimlop: warning: the board was not found "
              << (charuco ? formatText("(%d corners or more) ", o.calibration.minCornersPerView)
                          : std::string("whole "))
              << "in " << fit.viewsWithoutBoard.size()
              << " view(s), left out: " << joinList(fit.viewsWithoutBoard) << "\n";
  }
  writeIntrinsics(fit.intrinsics, o.out);
  const PinholeCamera& k = fit.intrinsics;
  std::string coefficients;
  for (int i = 0; i < k.distortion.size(); ++i)
  {
    coefficients += formatText(i ? ", %.4g" : "%.4g", k.distortion[i]);
  }
  const char* lens = o.fisheye ? "fisheye" : "radial-tangential";
  CommandSummary summary;
  summary.lines.push_back(
    formatText("calibrate: %zu of %d views show the %s %s (%d corners); fx %.2f fy %.2f cx %.2f cy "
               "%.2f px, %s (%s); RMS reprojection error %.3f px; wrote '%s'",
      fit.viewsUsed.size(), views.size(), o.board.c_str(), charuco ? "ChArUco board" : "board",
      fit.cornersUsed, k.fx, k.fy, k.cx, k.cy, lens, coefficients.c_str(),
      fit.rmsReprojectionErrorPx, o.out.c_str()));
  summary.json = { { "views", views.size() }, { "views_used", fit.viewsUsed },
    { "views_without_board", fit.viewsWithoutBoard }, { "board", o.board },
    { "pattern", o.pattern }, { "corners_used", fit.cornersUsed },
    { "rms_reprojection_error_px", fit.rmsReprojectionErrorPx }, { "intrinsics", o.out } };
  summary.json.update(intrinsicsJson(k));
  printSummary(summary, o.json);
}

} // namespace

void addCalibrateCommand(CLI::App& app)
{
  auto o = std::make_shared<CalibrateOptions>();
  CLI::App* calibrate = app.add_subcommand("calibrate",
    "Calibrate the endoscope's camera from views of a chessboard or ChArUco board (OpenCV): the "
    "intrinsics file "
    "register, sfm and contours read");
  calibrate->add_option("--frames", o->frames, "folder of pictures (or a video) of the board")
    ->required();
  calibrate->add_option("--out", o->out, "intrinsics file to write (.yaml, .json, .xml)")
    ->required();
  calibrate
    ->add_option("--board", o->board,
      "inner corners of the board, COLUMNSxROWS (a ChArUco board has one square more each way)")
    ->capture_default_str();
  calibrate
    ->add_option("--pattern", o->pattern,
      "chessboard (every inner corner in every view used) or charuco (a ChArUco board: its "
      "markers name the corners, so views that show part of it count)")
    ->capture_default_str()
    ->check(CLI::IsMember({ "chessboard", "charuco" }));
  calibrate->add_option("--marker-mm", o->calibration.markerMm, "ChArUco: side of one marker, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  calibrate
    ->add_option("--dictionary", o->calibration.dictionary,
      "ChArUco: the ArUco dictionary of the markers (OpenCV's name without DICT_)")
    ->capture_default_str();
  calibrate
    ->add_option("--min-corners", o->calibration.minCornersPerView,
      "ChArUco: least corners a view must show to be used")
    ->capture_default_str()
    ->check(CLI::Range(6, 100000));
  calibrate->add_option("--square-mm", o->calibration.squareMm, "side of one square, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  calibrate->add_flag("--fisheye", o->fisheye,
    "fit OpenCV's fisheye model (k1..k4; wide-angle endoscopes) instead of its default "
    "radial-tangential one (k1, k2, p1, p2)");
  calibrate->add_option("--min-views", o->calibration.minViews, "least views showing the board")
    ->capture_default_str()
    ->check(CLI::Range(3, 1000));
  addJsonFlag(*calibrate, o->json);
  calibrate->callback([o] { runCalibrate(*o); });
}

} // namespace vimlop
