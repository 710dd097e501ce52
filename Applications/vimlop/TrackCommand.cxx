#include "CommandLine.h"
#include "Commands.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Pipeline/VideoTracking.h>
#include <vimlop/Server/LivePoseStream.h>

#include <CLI/CLI.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

namespace vimlop
{

namespace
{

struct TrackOptions
{
  VideoTrackingInputs inputs;
  VideoTrackingOptions tracking;
  bool noVideo = false;
  bool noContourCheck = false;
  bool serve = false;
  double waitForClientS = 0.0;
  PoseStreamServerOptions server;
  bool json = false;
};

void runTrack(const TrackOptions& o)
{
  namespace fs = std::filesystem;
  if (o.inputs.framesPath.empty() == (o.inputs.cameraIndex < 0))
  {
    throw Error("give exactly one of --frames and --camera");
  }
  VideoTrackingOptions options = o.tracking;
  options.writeVideo = !o.noVideo;
  options.checkContours = !o.noContourCheck;
  VideoTracking tracking(options);
  tracking.open(o.inputs);
  std::unique_ptr<LivePoseStream> server;
  if (o.serve)
  {
    server = std::make_unique<LivePoseStream>(o.server, "vimlop track");
    if (o.waitForClientS > 0.0 && !server->waitForClient(o.waitForClientS))
    {
      std::cerr << formatText("vimlop: warning: no client connected within %g s "
                              "(--wait-for-client-s); tracking starts anyway\n",
        o.waitForClientS);
    }
    // Each pose is sent as soon as it is computed, inside its latency.
    tracking.setFrameHandler(
      [&server](const TrackedVideoFrame& f)
      {
        if (f.tracked.state == TrackingState::Lost)
        {
          server->sendLost(f.frameId, f.tracked.reason);
        }
        else
        {
          server->sendPose({ f.frameId, f.tracked.cameraToCT }, f.tracked.reason);
        }
      });
  }
  // Ctrl-C (the way a live camera's tracking ends) stops after the frame in
  // hand, and what was tracked is written.
  InterruptGuard interrupt;
  tracking.setStopRequest([&interrupt] { return interrupt.requested(); });
  tracking.run();
  if (server && !server->finish(5.0))
  {
    std::cerr << "vimlop: warning: a client had not taken every pose 5 s after the last frame\n";
  }
  const std::size_t n = tracking.frames().size();
  const Summary latencyMs = tracking.latencyMs();
  CommandSummary summary;
  summary.lines.push_back(formatText("vimlop track: %zu frames from '%s': %d tracking, %d "
                                     "degraded, %d lost; latency %.1f ms median, %.1f ms p99",
    n, n > 0 ? tracking.frames().front().source.c_str() : "",
    tracking.count(TrackingState::Tracking), tracking.count(TrackingState::Degraded),
    tracking.count(TrackingState::Lost), latencyMs.median, latencyMs.p99));
  summary.json = tracking.report();
  summary.json.erase("per_frame");
  if (summary.json.contains("contour_error_px"))
  {
    summary.lines.push_back(formatText("contours against the CT: %.2f px median, %.2f px p95 "
                                       "(each frame's median distance to the model's contours); "
                                       "check and refinement %.1f ms median after each pose",
      summary.json["contour_error_px"]["median"].get<double>(),
      summary.json["contour_error_px"]["p95"].get<double>(),
      summary.json["check_ms"]["median"].get<double>()));
  }
  if (summary.json.contains("tracker"))
  {
    const nlohmann::json& tracker = summary.json["tracker"];
    for (const nlohmann::json& warning : tracker["warnings"])
    {
      std::cerr << "vimlop: warning: " << warning.get<std::string>() << "\n";
    }
    const int without = tracker["frames_without_tip"].get<int>();
    const char* given = tracker["rotation"].get<bool>() ? "tip and rotation" : "tip";
    summary.lines.push_back(without == 0
        ? formatText("the tracker's %s were given for every frame", given)
        : formatText("%d frames lie outside the tracker's recording and were tracked without "
                     "its %s (--time-offset, --fps)",
            without, given));
    if (tracker.contains("offset"))
    {
      const nlohmann::json& offset = tracker["offset"];
      double squaredMm = 0.0;
      for (const nlohmann::json& axis : offset["shift_mm"])
      {
        squaredMm += axis.get<double>() * axis.get<double>();
      }
      summary.lines.push_back(formatText("the tracker's error, as the video anchored to the CT "
                                         "saw it in %d frames: %.2f mm, %.2f degrees",
        offset["frames_learned"].get<int>(), std::sqrt(squaredMm),
        offset["turn_deg"].get<double>()));
    }
    if (!tracker["lag"].is_null())
    {
      // The lag found is what --time-offset would take off in another run.
      summary.lines.push_back(formatText("the tracker's lag, as the video's motion showed it "
                                         "over %d pairs of frames: %.1f ms (its readings were "
                                         "taken that much later from then on)",
        tracker["lag"]["pairs"].get<int>(), 1000.0 * tracker["lag"]["lag_s"].get<double>()));
    }
  }
  if (summary.json.contains("camera_position_error_mm"))
  {
    summary.lines.push_back(
      formatText("camera error against the truth (frames not lost): mean %.3f mm, max %.3f mm",
        summary.json["camera_position_error_mm"]["mean"].get<double>(),
        summary.json["camera_position_error_mm"]["max"].get<double>()));
  }
  const std::string& out = o.inputs.outputFolder;
  summary.lines.push_back("wrote '" + (fs::path(out) / "tracked-poses.json").string() +
    "', tracked-poses.vtt, tracking.json" + (o.noVideo ? "" : " and tracked-video.avi"));
  printSummary(summary, o.json);
  if (tracking.stopRequested())
  {
    std::cerr << formatText("vimlop track: interrupted after %zu frames; the frames tracked were "
                            "written to '%s'\n",
      n, out.c_str());
    throw ExitRequest{ 130 };
  }
  if (!tracking.stoppedBy().empty())
  {
    throw Error(formatText("tracking stopped after %zu frames: %s (the frames before it were "
                           "tracked and written to '%s')",
      n, tracking.stoppedBy().c_str(), out.c_str()));
  }
}

} // namespace

void addTrackCommand(CLI::App& app)
{
  auto o = std::make_shared<TrackOptions>();
  CLI::App* c = app.add_subcommand("track",
    "Follow the endoscope frame by frame after a registration (issue 16): from the last frame a "
    "result folder registered, the pose of every later frame in the CT, with its state "
    "(tracking, degraded, lost); OUT/tracked-poses.json and .vtt, OUT/tracking.json and "
    "OUT/tracked-video.avi; --serve streams the poses over OpenIGTLink as they are computed");
  c->add_option("--result", o->inputs.resultFolder, "result folder of vimlop register")->required();
  c->add_option("--frames", o->inputs.framesPath,
    "the frames to track, read one at a time as they come: a folder of frames, a video file or "
    "a tracked sequence");
  c->add_option("--camera", o->inputs.cameraIndex,
     "track live from the camera /dev/video<N> (a V4L2 device, e.g. a frame grabber) instead of "
     "--frames")
    ->check(CLI::NonNegativeNumber);
  c->add_option("--intrinsics", o->inputs.intrinsicsPath,
    "the camera's intrinsics file (as given to register): the frames are undistorted with its "
    "lens");
  c->add_option("--from", o->tracking.firstFrameIndex,
     "index of the first frame to track in --frames (default: the one after the registered frame "
     "of the same name, else 0)")
    ->check(CLI::NonNegativeNumber);
  c->add_option(
    "--truth", o->inputs.truthPath, "true camera poses (FramePose JSON): errors are reported");
  c->add_flag("--allow-flagged", o->tracking.allowFlagged,
    "track from a result the registration flagged as a failure (refused without it)");
  c->add_option("--out", o->inputs.outputFolder, "output folder")->required();
  c->add_flag("--no-video", o->noVideo,
    "do not write tracked-video.avi (each frame with the model's contours at its tracked pose, "
    "under a band with its state)");
  c->add_flag("--no-contour-check", o->noContourCheck,
    "do not check each tracked pose against the CT (the frame's occluding contours matched to the "
    "model's at the pose, after the pose is sent: the median error, px, is in tracking.json and "
    "the video's band)");
  addTrackingRefinementOptions(*c, o->tracking.refineAgainstCT, o->tracking.refinement);
  addTrackingRelocalisationOptions(*c, o->tracking.relocalise, o->tracking.relocalisation);
  c->add_option("--tracker", o->inputs.trackerPath,
    "the electromagnetic tracker's recording of the scope's tip: a CSV (time_s,x_mm,y_mm,z_mm, "
    "with qw,qx,qy,qz for a 6-DOF sensor), or a tracked sequence with --tracker-transform; its "
    "tip (and a 6-DOF sensor's rotation) at each frame's time is the prediction after a lost "
    "frame, and a pose more than 3 mm from it (or turned more than 5 degrees) is degraded "
    "(needs --tracker-to-ct)");
  c->add_option("--tracker-transform", o->inputs.trackerTransform,
    "the transform of a tracked sequence that carries the scope, e.g. ProbeToTracker: read from "
    "--tracker, or from --frames when it is a tracked sequence and --tracker is not given");
  c->add_option("--tracker-to-ct", o->inputs.trackerToCTPath,
    "the tracker registered to the patient, as 3D Slicer saves its TrackerToRAS transform (ITK "
    ".tfm/.h5)");
  c->add_option("--time-offset", o->inputs.timeOffsetS,
     "added to each frame's time on the tracker's clock: a tracked sequence's own timestamp, "
     "else the frame's place at --fps from 0, s")
    ->capture_default_str();
  c->add_option("--fps", o->tracking.videoFps,
     "the frames' rate, frames per second: the tracked video's, and the frames' times on the "
     "tracker's clock")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c->add_flag("--serve", o->serve,
    "stream each pose over OpenIGTLink as it is computed: a TRANSFORM of the moving camera (RAS "
    "mm) stamped when it is sent, followed by a STATUS TrackingDegraded for a degraded frame; a "
    "STATUS TrackingLost for a lost one");
  c->add_option("--wait-for-client-s", o->waitForClientS,
     "with --serve: wait up to this long for a first client before tracking (default 0: start at "
     "once)")
    ->check(CLI::NonNegativeNumber)
    ->needs("--serve");
  addPoseServerOptions(*c, o->server);
  addEndoscopeTrackerOptions(*c, o->tracking.tracker, o->tracking.trackerLag);
  addJsonFlag(*c, o->json);
  c->callback([o] { runTrack(*o); });
}

} // namespace vimlop
