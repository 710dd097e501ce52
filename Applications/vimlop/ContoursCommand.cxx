#include "ContoursCommand.h"

#include "CommandLine.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Video/FrameSequence.h>
#include <vimlop/Video/OccludingContourDetector.h>

#include <CLI/CLI.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace vimlop
{

namespace
{

struct ContoursOptions
{
  std::string frames;
  std::string out;
  std::string overlay;
  std::string channel = "luminance";
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
  const OccludingContourDetector detector(o.detector);
  nlohmann::json frames = nlohmann::json::array();
  size_t total = 0;
  for (int f = 0; f < sequence.size(); ++f)
  {
    const std::vector<ContourPoint> points = detector.detect(sequence.frame(f));
    total += points.size();
    nlohmann::json list = nlohmann::json::array();
    for (const ContourPoint& p : points)
    {
      list.push_back({ p.pixel.x(), p.pixel.y(), p.normal.x(), p.normal.y() });
    }
    frames.push_back({ { "name", sequence.name(f) }, { "points", list } });
    if (!o.overlay.empty())
    {
      // Each point as a dot with a short tick along its normal (towards the far side).
      cv::Mat picture = sequence.frame(f).clone();
      for (const ContourPoint& p : points)
      {
        const cv::Point2d a(p.pixel.x(), p.pixel.y());
        const cv::Point2d b = a + 4.0 * cv::Point2d(p.normal.x(), p.normal.y());
        cv::line(picture, a, b, cv::Scalar(255, 255, 0), 1, cv::LINE_AA);
        cv::circle(picture, a, 1, cv::Scalar(0, 255, 0), -1, cv::LINE_AA);
      }
      std::filesystem::create_directories(o.overlay);
      const std::string path =
        (std::filesystem::path(o.overlay) / sequence.name(f)).replace_extension(".png").string();
      if (!cv::imwrite(path, picture))
      {
        throw Error("'" + path + "': cannot write the image");
      }
    }
  }
  const nlohmann::json document = { { "format", "vimlop-contours" }, { "version", 1 },
    { "convention",
      "pixels with the centre of the top-left pixel at (0, 0); [u, v, nu, nv] with the unit normal "
      "pointing from the near, occluding side to the far side" },
    { "frames", frames } };
  writeJsonFile(document, o.out);
  std::printf("contours: %zu points in %d frames (%.0f per frame); wrote '%s'\n", total,
    sequence.size(), static_cast<double>(total) / sequence.size(), o.out.c_str());
}

} // namespace

void addContoursCommand(CLI::App& app)
{
  auto o = std::make_shared<ContoursOptions>();
  CLI::App* contours = app.add_subcommand(
    "contours", "Detect occluding contours with normals (near to far side) in every frame");
  contours->add_option("--frames", o->frames, "folder of frames or a video file")->required();
  contours->add_option("--out", o->out, "result JSON file")->required();
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
  contours->callback([o] { runContours(*o); });
}

} // namespace vimlop
