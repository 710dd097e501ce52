#include "CommandLine.h"
#include "Commands.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Pipeline/EndoscopeTracker.h>
#include <vimlop/Pipeline/TrackedVideoWriter.h>
#include <vimlop/Pipeline/TrackingStart.h>
#include <vimlop/Results/TrackedPoseTable.h>
#include <vimlop/Server/LivePoseStream.h>
#include <vimlop/Video/FrameStream.h>
#include <vimlop/Video/FrameUndistorter.h>
#include <vimlop/Video/IntrinsicsIO.h>

#include <CLI/CLI.hpp>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

namespace vimlop
{

namespace
{

struct TrackOptions
{
  std::string result;
  std::string frames;
  std::string intrinsics;
  std::string truth;
  std::string out;
  int camera = -1;
  int from = -1;
  bool allowFlagged = false;
  bool serve = false;
  bool noVideo = false;
  double fps = 30.0;
  double waitForClientS = 0.0;
  PoseStreamServerOptions server;
  EndoscopeTrackerOptions tracker;
  bool json = false;
};

/// The camera the frames are undistorted with: the intrinsics file's lens
/// around the camera the result registered with, which it must be.
PinholeCamera lensOf(const TrackOptions& o, const PinholeCamera& registered)
{
  if (o.intrinsics.empty())
  {
    return registered;
  }
  const PinholeCamera given = readIntrinsics(o.intrinsics);
  const PinholeCamera pinhole = FrameUndistorter(given).pinhole();
  const auto same = [](double a, double b)
  { return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(b)); };
  if (pinhole.widthPx != registered.widthPx || pinhole.heightPx != registered.heightPx ||
    !same(pinhole.fx, registered.fx) || !same(pinhole.fy, registered.fy) ||
    !same(pinhole.cx, registered.cx) || !same(pinhole.cy, registered.cy))
  {
    throwFileError(o.intrinsics,
      formatText("a %dx%d camera with fx %g, fy %g, cx %g, cy %g, but the result registered a "
                 "%dx%d camera with fx %g, fy %g, cx %g, cy %g: give the intrinsics the result "
                 "was registered with",
        pinhole.widthPx, pinhole.heightPx, pinhole.fx, pinhole.fy, pinhole.cx, pinhole.cy,
        registered.widthPx, registered.heightPx, registered.fx, registered.fy, registered.cx,
        registered.cy));
  }
  return given;
}

void runTrack(const TrackOptions& o)
{
  namespace fs = std::filesystem;
  o.tracker.validate();
  if (o.frames.empty() == (o.camera < 0))
  {
    throw Error("give exactly one of --frames and --camera");
  }
  const TrackingStart start = TrackingStart::fromResult(o.result);
  // Tracking carries the registration's error to every frame: a result the
  // registration itself flagged is no start for navigation.
  if (!start.failureReason.empty() && !o.allowFlagged)
  {
    throw Error("refusing to track from a result flagged as a failure (" + start.failureReason +
      "): every tracked pose would carry its error; pass --allow-flagged to track anyway");
  }
  // The frames as the registration saw them: undistorted with the lens of
  // the intrinsics file (the one given to `register`), or as they are.
  const FrameUndistorter undistorter(lensOf(o, start.intrinsics));
  FrameStream stream =
    o.camera >= 0 ? FrameStream::openCamera(o.camera) : FrameStream::open(o.frames);
  // By default tracking goes on after the frame the registration ended on.
  const std::optional<int> registeredAt =
    start.frameSource.empty() ? std::nullopt : stream.indexOfName(start.frameSource);
  const int first = o.from >= 0 ? o.from : registeredAt ? *registeredAt + 1 : 0;
  std::map<int, CameraPose> truth;
  if (!o.truth.empty())
  {
    for (const FramePose& p : readFramePoses(o.truth))
    {
      truth[p.frameId] = p.cameraToWorld;
    }
  }

  EndoscopeTracker tracker(start.modelCT, start.intrinsics, o.tracker);
  tracker.start(start.frame, start.cameraToCT, start.fieldOfViewMask);
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
  }
  fs::create_directories(o.out);
  // The tracked video is written as the frames come, after each pose is sent.
  std::unique_ptr<TrackedVideoWriter> video;
  if (!o.noVideo)
  {
    video = std::make_unique<TrackedVideoWriter>(
      start.modelCT, start.intrinsics, (fs::path(o.out) / "tracked-video.avi").string(), o.fps);
  }
  std::vector<FramePose> poses;
  std::vector<TrackedPoseRow> rows;
  nlohmann::json records = nlohmann::json::array();
  std::vector<double> latency, errorMm;
  int counts[3] = { 0, 0, 0 };
  std::string firstName;
  std::string stoppedBy;
  StreamedFrame f;
  int seen = 0;
  // Ctrl-C (the way a live camera's tracking ends) stops after the frame in
  // hand, and what was tracked is written.
  InterruptGuard interrupt;
  try
  {
    for (; !interrupt.requested() && stream.next(f); ++seen)
    {
      if (f.index < first)
      {
        continue;
      }
      if (f.image.size() != cv::Size(start.intrinsics.widthPx, start.intrinsics.heightPx))
      {
        throw Error(formatText("frame '%s' of %s is %dx%d pixels, but the result's camera is "
                               "%dx%d: these are not the frames it registered",
          f.name.c_str(), stream.source().c_str(), f.image.cols, f.image.rows,
          start.intrinsics.widthPx, start.intrinsics.heightPx));
      }
      // The latency is the whole way from the decoded frame to its pose
      // (sent, with --serve): undistortion, tracking and serving.
      const auto decoded = std::chrono::steady_clock::now();
      const cv::Mat ideal = undistorter.undistort(f.image);
      const TrackedFrame t = tracker.track(ideal);
      firstName = firstName.empty() ? f.name : firstName;
      ++counts[static_cast<int>(t.state)];
      nlohmann::json record = { { "frame_id", f.id }, { "source", f.name },
        { "state", toString(t.state) }, { "tracked_features", t.trackedFeatures },
        { "inliers", t.inliers }, { "reprojection_error_px", t.reprojectionErrorPx },
        { "new_features", t.newFeatures } };
      const auto known = truth.find(f.id);
      if (known != truth.end())
      {
        const double mm = cameraPositionError(t.cameraToCT, known->second);
        record["camera_position_error_mm"] = mm;
        record["camera_angle_error_deg"] = cameraAngleErrorDeg(t.cameraToCT, known->second);
        if (t.state != TrackingState::Lost)
        {
          errorMm.push_back(mm);
        }
      }
      if (!t.reason.empty())
      {
        record["reason"] = t.reason;
      }
      records.push_back(record);
      if (t.state != TrackingState::Lost)
      {
        poses.push_back({ f.id, t.cameraToCT });
      }
      if (server && t.state == TrackingState::Lost)
      {
        server->sendLost(f.id, t.reason);
      }
      else if (server)
      {
        server->sendPose(poses.back(), t.reason);
      }
      latency.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - decoded)
          .count());
      records.back()["latency_ms"] = latency.back();
      rows.push_back({ { f.id, t.cameraToCT }, toString(t.state), latency.back() });
      if (video)
      {
        video->write(ideal, t, f.name);
      }
    }
  }
  catch (const Error& e)
  {
    // The frames tracked before it are written all the same. (A camera or
    // decoder may fail because of the interruption itself: that is no error.)
    stoppedBy = interrupt.requested() ? std::string() : e.what();
  }
  const bool interrupted = interrupt.requested();
  if (records.empty() && !stoppedBy.empty())
  {
    throw Error(stoppedBy);
  }
  if (records.empty() && !interrupted)
  {
    throw Error(formatText("no frames to track: '%s' has %d frames, and tracking would start at "
                           "frame %d (after the registered frame '%s'; --from sets it)",
      stream.source().c_str(), seen, first, start.frameSource.c_str()));
  }
  if (server && !server->finish(5.0))
  {
    std::cerr << "vimlop: warning: a client had not taken every pose 5 s after the last frame\n";
  }

  video.reset();
  // Lost frames have no pose a navigation system should show: they are in
  // tracking.json with their state, not in the pose file.
  writeFramePoses(poses, (fs::path(o.out) / "tracked-poses.json").string());
  // Every frame, with its state, for VTK pipelines.
  writeTrackedPoseTable(rows, (fs::path(o.out) / "tracked-poses.vtt").string());
  const Summary latencyMs = summarize(latency);
  nlohmann::json report = { { "result", o.result }, { "frames", stream.source() },
    { "start_frame_id", start.frameId }, { "first_tracked_index", first },
    { "tracking", counts[0] }, { "degraded", counts[1] }, { "lost", counts[2] },
    { "latency_ms", { { "median", latencyMs.median }, { "p99", latencyMs.p99 } } },
    { "per_frame", records } };
  if (!stoppedBy.empty() || interrupted)
  {
    report["stopped_by"] = interrupted ? "interrupted (Ctrl-C or SIGTERM)" : stoppedBy;
  }
  CommandSummary summary;
  summary.lines.push_back(formatText("vimlop track: %zu frames from '%s': %d tracking, %d "
                                     "degraded, %d lost; latency %.1f ms median, %.1f ms p99",
    records.size(), firstName.c_str(), counts[0], counts[1], counts[2], latencyMs.median,
    latencyMs.p99));
  if (!errorMm.empty())
  {
    const Summary e = summarize(errorMm);
    report["camera_position_error_mm"] = { { "mean", e.mean }, { "max", e.max } };
    summary.lines.push_back(
      formatText("camera error against the truth (frames not lost): mean %.3f mm, max %.3f mm",
        e.mean, e.max));
  }
  writeJsonFile(report, (fs::path(o.out) / "tracking.json").string());
  summary.lines.push_back("wrote '" + (fs::path(o.out) / "tracked-poses.json").string() +
    "', tracked-poses.vtt, tracking.json" + (o.noVideo ? "" : " and tracked-video.avi"));
  summary.json = report;
  summary.json.erase("per_frame");
  printSummary(summary, o.json);
  if (interrupted)
  {
    std::cerr << formatText("vimlop track: interrupted after %zu frames; the frames tracked were "
                            "written to '%s'\n",
      records.size(), o.out.c_str());
    throw ExitRequest{ 130 };
  }
  if (!stoppedBy.empty())
  {
    throw Error(formatText("tracking stopped after %zu frames: %s (the frames before it were "
                           "tracked and written to '%s')",
      records.size(), stoppedBy.c_str(), o.out.c_str()));
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
  c->add_option("--result", o->result, "result folder of vimlop register")->required();
  c->add_option("--frames", o->frames,
    "the frames to track, read one at a time as they come: a folder of frames, a video file or "
    "a tracked sequence");
  c->add_option("--camera", o->camera,
     "track live from the camera /dev/video<N> (a V4L2 device, e.g. a frame grabber) instead of "
     "--frames")
    ->check(CLI::NonNegativeNumber);
  c->add_option("--intrinsics", o->intrinsics,
    "the camera's intrinsics file (as given to register): the frames are undistorted with its "
    "lens");
  c->add_option("--from", o->from,
     "index of the first frame to track in --frames (default: the one after the registered frame "
     "of the same name, else 0)")
    ->check(CLI::NonNegativeNumber);
  c->add_option("--truth", o->truth, "true camera poses (FramePose JSON): errors are reported");
  c->add_flag("--allow-flagged", o->allowFlagged,
    "track from a result the registration flagged as a failure (refused without it)");
  c->add_option("--out", o->out, "output folder")->required();
  c->add_flag("--no-video", o->noVideo,
    "do not write tracked-video.avi (each frame with the model's contours at its tracked pose, "
    "under a band with its state)");
  c->add_option("--fps", o->fps, "the tracked video's rate, frames per second")
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
  c->add_option("--max-features", o->tracker.maxFeatures, "features tracked at most")
    ->capture_default_str();
  c->add_option("--max-tracking-width-px", o->tracker.maxTrackingWidthPx,
     "frames wider than this are tracked halved until they fit (the tracker's pixel settings "
     "are for frames about 320 px wide)")
    ->capture_default_str();
  c->add_option("--inlier-px", o->tracker.inlierThresholdPx,
     "a feature agrees with a pose within this reprojection error, px")
    ->capture_default_str();
  addJsonFlag(*c, o->json);
  c->callback([o] { runTrack(*o); });
}

} // namespace vimlop
