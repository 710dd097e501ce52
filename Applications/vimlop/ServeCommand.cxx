#include "CommandLine.h"
#include "Commands.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Results/RegistrationRecordIO.h>
#include <vimlop/Results/RegistrationVerdict.h>
#include <vimlop/Server/PoseServing.h>

#include <CLI/CLI.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <filesystem>
#include <memory>

namespace vimlop
{

namespace
{

struct ServeOptions
{
  std::string poses;
  std::string result;
  bool images = false;
  PoseServingOptions serving;
};

/// The pictures of a result folder's registered frames, in the order of its poses.
std::vector<FramePicture> framePicturesOf(
  const RegistrationRecord& record, const std::string& folder)
{
  std::vector<FramePicture> pictures;
  for (size_t j = 0; j < record.result.frames.size(); ++j)
  {
    const std::string path = j < record.frameImages.size() && !record.frameImages[j].empty()
      ? (std::filesystem::path(folder) / record.frameImages[j]).string()
      : std::string();
    const cv::Mat bgr = path.empty() ? cv::Mat() : cv::imread(path, cv::IMREAD_COLOR);
    if (bgr.empty())
    {
      throwFileError(folder,
        "frame " + std::to_string(record.result.frames[j].frameId) + " has no readable picture" +
          (path.empty() ? std::string() : " ('" + path + "')") + ", so --images cannot send it");
    }
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    FramePicture picture;
    picture.widthPx = rgb.cols;
    picture.heightPx = rgb.rows;
    picture.rgb.assign(rgb.datastart, rgb.dataend);
    pictures.push_back(std::move(picture));
  }
  return pictures;
}

void runServe(const ServeOptions& options)
{
  if (options.poses.empty() == options.result.empty())
  {
    throw Error("give exactly one of --poses and --result");
  }
  ServedPoses poses;
  if (!options.poses.empty())
  {
    poses.cameraToCT = readFramePoses(options.poses);
  }
  else
  {
    const RegistrationRecord record = readRegistrationRecord(options.result);
    poses = servedPosesOf(record);
    if (options.images)
    {
      poses.pictures = framePicturesOf(record, options.result);
    }
  }
  servePoses(options.serving, poses);
}

} // namespace

ServedPoses servedPosesOf(const RegistrationRecord& record)
{
  ServedPoses poses = servedPosesOf(record.result);
  const std::vector<VideoFrame>& frames = record.data.frames;
  if (record.frameTimesS.size() == frames.size())
  {
    // Result frames are data frames with a pose: matched by id.
    for (const FramePose& pose : poses.cameraToCT)
    {
      const auto at = std::find_if(frames.begin(), frames.end(),
        [&](const VideoFrame& frame) { return frame.frameId == pose.frameId; });
      if (at == frames.end())
      {
        throw Error("the result's frame " + std::to_string(pose.frameId) +
          " is not in its frame table: the record has no time for it");
      }
      poses.frameTimesS.push_back(record.frameTimesS[static_cast<size_t>(at - frames.begin())]);
    }
  }
  for (const RegistrationRecord::FrameWithoutPose& f : record.framesWithoutPose)
  {
    poses.framesWithoutPose.push_back({ f.frameId, f.timeS, "SfM did not register it" });
  }
  if (const auto& c = record.confidence)
  {
    const std::string reason = c->reason.empty() ? "flagged as a failure" : c->reason;
    poses.verdict =
      PoseVerdict{ c->failure, c->failure ? reason : RegistrationVerdict::of(record).headline() };
  }
  return poses;
}

void addServeCommand(CLI::App& app)
{
  auto options = std::make_shared<ServeOptions>();
  CLI::App* serve = app.add_subcommand("serve",
    "Send camera poses to navigation software (3D Slicer OpenIGTLinkIF, PLUS, ...) over "
    "OpenIGTLink");
  serve->add_option("--poses", options->poses,
    "camera poses in CT (JSON, as written by vimlop warp), sent in their order as the moving "
    "camera (or VideoCamera_<frame id> with --per-frame-names)");
  serve->add_option("--result", options->result,
    "a registration's result folder: each frame's camera-to-CT pose stamped with its frame's "
    "time, the SfM-to-CT similarity as CTFromSfM and the verdict as a STATUS message; a result "
    "flagged as a failure is refused without --allow-flagged");
  serve
    ->add_flag("--images", options->images,
      "with --result: each frame's picture before its pose, as an IMAGE message (--image-name) "
      "with the same time, so that 3D Slicer shows the video beside the virtual view")
    ->needs("--result");
  serve
    ->add_option("--image-name", options->serving.server.imageName,
      "device name of the IMAGE messages (1 to 20 characters)")
    ->capture_default_str()
    ->needs("--images");
  addPoseServingOptions(*serve, options->serving);
  serve->callback([options] { runServe(*options); });
}

} // namespace vimlop
