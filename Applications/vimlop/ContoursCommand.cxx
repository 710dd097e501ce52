#include "CommandLine.h"
#include "Commands.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Video/FrameContoursIO.h>
#include <vimlop/Video/FrameSequence.h>
#include <vimlop/Video/IntrinsicsIO.h>
#include <vimlop/Video/OccludingContourDetector.h>
#include <vimlop/Video/VideoInput.h>

#include <CLI/CLI.hpp>

#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace vimlop
{

namespace
{

struct ContoursOptions
{
  std::string frames;
  std::string intrinsics;
  std::string out;
  std::string overlay;
  bool json = false;
  // vimlop register's default (ContourDetectionOptions), so that its --contours reuses the same
  // points.
  std::string channel =
    ContourDetectionOptions().channel == ContourChannel::Red ? "red" : "luminance";
  ContourDetectionOptions detector;
};

void runContours(ContoursOptions o)
{
  if (o.channel == "luminance")
  {
    o.detector.channel = ContourChannel::Luminance;
  }
  else if (o.channel == "red")
  {
    o.detector.channel = ContourChannel::Red;
  }
  else
  {
    throw Error("--channel: expected 'luminance' or 'red', got '" + o.channel + "'");
  }
  const FrameSequence sequence = FrameSequence::load(o.frames);
  // With intrinsics, the frames as the registration sees them: undistorted.
  FrameContoursPictures pictures;
  std::vector<cv::Mat> undistorted;
  if (!o.intrinsics.empty())
  {
    undistorted =
      idealFrames(sequence, readIntrinsics(o.intrinsics), o.frames, o.intrinsics, &std::cerr);
    pictures.undistorted = true;
  }
  const OccludingContourDetector detector(o.detector);
  std::vector<FrameContours> frames;
  size_t total = 0;
  for (int f = 0; f < sequence.size(); ++f)
  {
    const cv::Mat& picture = undistorted.empty() ? sequence.frame(f) : undistorted[f];
    pictures.widthPx = picture.cols;
    pictures.heightPx = picture.rows;
    frames.push_back({ sequence.name(f), detector.detect(picture) });
    total += frames.back().points.size();
    if (!o.overlay.empty())
    {
      std::filesystem::create_directories(o.overlay);
      const std::string path =
        (std::filesystem::path(o.overlay) / sequence.name(f)).replace_extension(".png").string();
      if (!cv::imwrite(path, drawFrameContours(picture, frames.back().points)))
      {
        throwFileError(path, "cannot write the image");
      }
    }
  }
  writeFrameContours(frames, pictures, o.out);
  CommandSummary summary;
  summary.lines.push_back(
    formatText("contours: %zu points in %d frames (%.0f per frame); wrote '%s'", total,
      sequence.size(), static_cast<double>(total) / sequence.size(), o.out.c_str()));
  nlohmann::json perFrame = nlohmann::json::array();
  for (const FrameContours& frame : frames)
  {
    perFrame.push_back({ { "frame", frame.name }, { "points", frame.points.size() } });
  }
  summary.json = { { "points", total }, { "frames", perFrame },
    { "undistorted", pictures.undistorted }, { "out", o.out } };
  printSummary(summary, o.json);
}

} // namespace

void addContoursCommand(CLI::App& app)
{
  auto o = std::make_shared<ContoursOptions>();
  CLI::App* contours = app.add_subcommand(
    "contours", "Detect occluding contours with normals (near to far side) in every frame");
  contours->add_option("--frames", o->frames, "folder of frames or a video file")->required();
  contours->add_option("--out", o->out, "result JSON file")->required();
  contours->add_option("--intrinsics", o->intrinsics,
    "camera intrinsics (OpenCV YAML/JSON/XML): detect in the undistorted frames, as vimlop "
    "register does, so that register --contours can reuse the file");
  contours->add_option(
    "--overlay", o->overlay, "folder for pictures of the contours over the frames");
  contours->add_option("--channel", o->channel, "image channel: luminance or red")
    ->capture_default_str();
  contours->add_option("--smoothing-px", o->detector.smoothingSigmaPx, "Gaussian smoothing, pixels")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  contours
    ->add_option(
      "--high", o->detector.highThreshold, "high hysteresis threshold, log intensity per pixel")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  contours
    ->add_option(
      "--low", o->detector.lowThreshold, "low hysteresis threshold, log intensity per pixel")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  contours
    ->add_option("--spacing-px", o->detector.spacingPx, "least distance between points, pixels")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  addJsonFlag(*contours, o->json);
  contours->callback([o] { runContours(*o); });
}

} // namespace vimlop
