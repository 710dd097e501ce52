#include <vimlop/Server/PoseServing.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/RegistrationResult.h>

#include <chrono>
#include <csignal>
#include <cstdio>

namespace vimlop
{

namespace
{

volatile std::sig_atomic_t stopRequested = 0;

void requestStop(int)
{
  stopRequested = 1;
}

} // namespace

ServedPoses servedPosesOf(const RegistrationResult& result)
{
  ServedPoses poses;
  poses.ctFromSfm = result.sfmToCT;
  for (const FrameResult& frame : result.frames)
  {
    poses.cameraToCT.push_back({ frame.frameId, frame.cameraToCT });
  }
  return poses;
}

void servePoses(const PoseServingOptions& options, const ServedPoses& poses)
{
  if (poses.verdict && poses.verdict->flagged && !options.allowFlagged)
  {
    throw Error("refusing to serve a result flagged as a failure (" + poses.verdict->text +
      "): navigation would show it like any other; pass --allow-flagged to serve it anyway "
      "(clients are told by a STATUS message)");
  }
  PoseStreamServer server(withNoticesOnStderr(options.server, options.label));
  server.publish(poses);
  stopRequested = 0;
  const auto previousInt = std::signal(SIGINT, requestStop);
  const auto previousTerm = std::signal(SIGTERM, requestStop);
  const bool oneDevice = options.server.cameraNames == CameraDeviceNames::OneMovingCamera;
  const std::string devices = oneDevice ? "as " + options.server.cameraName : "as VideoCamera_<id>";
  std::string also;
  if (!poses.pictures.empty())
  {
    also += "; their frames as IMAGE " + options.server.imageName;
  }
  if (!poses.framesWithoutPose.empty())
  {
    also += "; " + std::to_string(poses.framesWithoutPose.size()) +
      " frame(s) without a pose as STATUS TrackingLost";
  }
  std::printf("%s: %zu camera poses %s%s%s on %s:%d (OpenIGTLink TRANSFORM, RAS mm%s); Ctrl-C "
              "stops\n",
    options.label.c_str(), poses.cameraToCT.size(), devices.c_str(),
    poses.ctFromSfm ? ", CTFromSfM" : "",
    poses.verdict ? (poses.verdict->flagged ? ", STATUS flagged" : ", STATUS OK") : "",
    options.server.host.c_str(), server.port(), also.c_str());
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  try
  {
    server.serve(
      [&]
      {
        const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return !stopRequested && (options.durationS <= 0.0 || elapsed < options.durationS) &&
          (!options.keepServing || options.keepServing());
      });
  }
  catch (...)
  {
    std::signal(SIGINT, previousInt);
    std::signal(SIGTERM, previousTerm);
    throw;
  }
  std::signal(SIGINT, previousInt);
  std::signal(SIGTERM, previousTerm);
  std::printf("%s: stopped\n", options.label.c_str());
  std::fflush(stdout);
}

} // namespace vimlop
