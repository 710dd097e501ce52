#include "SfmCommand.h"

#include "ColmapImport.h"
#include "Error.h"
#include "FrameSequence.h"
#include "IntrinsicsIO.h"
#include "SfmReconstructionIO.h"
#include "StructureFromMotion.h"
#include "TrackerScale.h"

#include <CLI/CLI.hpp>

#include <opencv2/calib3d.hpp>

#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

namespace vimlop
{

namespace
{

struct SfmOptions
{
  std::string frames;
  std::string intrinsics;
  std::string colmap;
  std::string out;
  std::string tracker;
  double fps = 30.0;
  double timeOffset = 0.0;
};

void runSfm(const SfmOptions& o)
{
  // The tracker file is checked before the work, so that a bad one fails fast.
  std::vector<std::string> trackerWarnings;
  std::optional<TrackerTrajectory> tracker;
  if (!o.tracker.empty())
  {
    tracker = TrackerTrajectory::readCsv(o.tracker, &trackerWarnings);
  }
  auto frameTimes = [&](size_t count)
  {
    std::vector<double> times;
    for (size_t f = 0; f < count; ++f)
    {
      times.push_back(o.timeOffset + static_cast<double>(f) / o.fps);
    }
    return times;
  };
  SfmReconstruction sfm;
  if (!o.colmap.empty())
  {
    std::vector<std::string> names;
    if (!o.frames.empty())
    {
      const FrameSequence sequence = FrameSequence::load(o.frames);
      for (int f = 0; f < sequence.size(); ++f)
      {
        names.push_back(sequence.name(f));
      }
    }
    std::vector<std::string> warnings;
    sfm = readColmapModel(o.colmap, ColmapFormat::Automatic, names, 0.5, &warnings);
    for (const std::string& w : warnings)
    {
      std::cerr << "vimlop: warning: " << w << "\n";
    }
  }
  else
  {
    if (o.frames.empty() || o.intrinsics.empty())
    {
      throw Error("give --frames and --intrinsics (or --colmap to import a COLMAP model)");
    }
    const PinholeCamera k = readIntrinsics(o.intrinsics);
    const FrameSequence sequence = FrameSequence::load(o.frames);
    if (tracker)
    {
      checkTrackerOverlap(*tracker, frameTimes(static_cast<size_t>(sequence.size())));
    }
    if (k.widthPx != sequence.widthPx() || k.heightPx != sequence.heightPx())
    {
      throw Error("'" + o.intrinsics + "': the intrinsics are for " + std::to_string(k.widthPx) +
        "x" + std::to_string(k.heightPx) + " pixels but the frames in '" + o.frames + "' are " +
        std::to_string(sequence.widthPx()) + "x" + std::to_string(sequence.heightPx()));
    }
    // SfM works on ideal pinhole frames: lens distortion is removed first.
    const bool distorted = k.distortion.size() > 0 && !k.distortion.isZero();
    cv::Mat matrix;
    cv::Mat coefficients;
    if (distorted)
    {
      std::cerr
        << "vimlop: note: undistorting the frames with the intrinsics' distortion coefficients\n";
      matrix = (cv::Mat_<double>(3, 3) << k.fx, 0.0, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0);
      coefficients = cv::Mat(1, static_cast<int>(k.distortion.size()), CV_64F);
      for (int i = 0; i < coefficients.cols; ++i)
      {
        coefficients.at<double>(i) = k.distortion[i];
      }
    }
    std::vector<cv::Mat> frames;
    std::vector<std::string> names;
    for (int f = 0; f < sequence.size(); ++f)
    {
      cv::Mat frame = sequence.frame(f);
      if (distorted)
      {
        cv::Mat undistorted;
        cv::undistort(frame, undistorted, matrix, coefficients);
        frame = undistorted;
      }
      frames.push_back(frame);
      names.push_back(sequence.name(f));
    }
    PinholeCamera ideal = k;
    ideal.distortion.resize(0);
    sfm = StructureFromMotion().reconstruct(frames, ideal, names, &std::cerr);
  }
  for (const SfmReconstruction::Frame& f : sfm.frames)
  {
    if (!f.registered)
    {
      std::cerr << "vimlop: warning: frame '" << f.name << "' was not registered; it is dropped\n";
    }
  }
  if (tracker)
  {
    std::vector<std::string> warnings = trackerWarnings;
    const std::vector<double> times = frameTimes(sfm.frames.size());
    std::vector<Eigen::Vector3d> centres;
    for (size_t f = 0; f < sfm.frames.size(); ++f)
    {
      centres.push_back(sfm.frames[f].registered
          ? sfm.frames[f].cameraToSfm.centre
          : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
    }
    const TrackerScaleResult scale = estimateTrackerScale(*tracker, times, centres);
    warnings.insert(warnings.end(), scale.warnings.begin(), scale.warnings.end());
    for (const std::string& w : warnings)
    {
      std::cerr << "vimlop: warning: " << w << "\n";
    }
    sfm.trackerScale = scale.scale;
    std::printf("tracker scale: 1 SfM unit = %.4f mm (tracked %.2f mm over %zu frames)\n",
      scale.scale, scale.trackerLengthMm, scale.framesUsed.size());
  }
  writeSfmReconstruction(sfm, o.out);
  std::printf(
    "SfM (%s): %d/%zu frames registered, %zu points, RMS reprojection error %.3f px; wrote '%s'\n",
    sfm.source.c_str(), sfm.numberOfRegisteredFrames(), sfm.frames.size(), sfm.points.size(),
    sfm.rmsReprojectionErrorPx(), o.out.c_str());
}

} // namespace

void addSfmCommand(CLI::App& app)
{
  auto o = std::make_shared<SfmOptions>();
  CLI::App* sfm = app.add_subcommand("sfm",
    "Structure from motion of a frame sequence: points, SfM-frame camera poses and covariances "
    "(built in, or imported from a COLMAP model)");
  sfm->add_option("--frames", o->frames, "folder of frames or a video file");
  sfm->add_option("--intrinsics", o->intrinsics, "camera intrinsics (OpenCV YAML/JSON/XML)");
  sfm->add_option(
    "--colmap", o->colmap, "import this COLMAP sparse model folder (text or binary) instead");
  sfm->add_option("--out", o->out, "result file (VIMLOP SfM JSON)")->required();
  sfm->add_option(
    "--tracker", o->tracker, "electromagnetic tracker CSV (time_s,x_mm,y_mm,z_mm): initial scale");
  sfm->add_option("--fps", o->fps, "frame rate, for the frame times on the tracker's clock")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  sfm
    ->add_option(
      "--time-offset", o->timeOffset, "time of the first frame on the tracker's clock, s")
    ->capture_default_str();
  sfm->callback([o] { runSfm(*o); });
}

} // namespace vimlop
