#include "CommandLine.h"
#include "Commands.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Results/RegistrationRecordIO.h>
#include <vimlop/Server/PoseServing.h>

#include <CLI/CLI.hpp>

#include <memory>

namespace vimlop
{

namespace
{

struct ServeOptions
{
  std::string poses;
  std::string result;
  PoseServingOptions serving;
};

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
    poses = servedPosesOf(readRegistrationRecord(options.result).result);
  }
  servePoses(options.serving, poses);
}

} // namespace

void addServeCommand(CLI::App& app)
{
  auto options = std::make_shared<ServeOptions>();
  CLI::App* serve = app.add_subcommand("serve",
    "Send camera poses to navigation software (3D Slicer OpenIGTLinkIF, PLUS, ...) over "
    "OpenIGTLink");
  serve->add_option("--poses", options->poses,
    "camera poses in CT (JSON, as written by vimlop warp); each becomes VideoCamera_<frame_id>");
  serve->add_option("--result", options->result,
    "a registration's result folder: each frame's camera-to-CT pose as VideoCamera_<frame id> and "
    "the SfM-to-CT similarity as CTFromSfM");
  addPoseServingOptions(*serve, options->serving);
  serve->callback([options] { runServe(*options); });
}

} // namespace vimlop
