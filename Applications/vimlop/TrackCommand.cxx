#include "CommandLine.h"
#include "Commands.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Pipeline/EndoscopeTracker.h>
#include <vimlop/Pipeline/TrackingStart.h>
#include <vimlop/Server/LivePoseStream.h>
#include <vimlop/Video/FieldOfView.h>
#include <vimlop/Video/FrameSequence.h>
#include <vimlop/Video/IntrinsicsIO.h>
#include <vimlop/Video/VideoInput.h>

#include <CLI/CLI.hpp>

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
  int from = -1;
  bool allowFlagged = false;
  bool serve = false;
  double waitForClientS = 0.0;
  PoseStreamServerOptions server;
  EndoscopeTrackerOptions tracker;
  bool json = false;
};

void runTrack(const TrackOptions& o)
{
  namespace fs = std::filesystem;
  o.tracker.validate();
  const TrackingStart start = TrackingStart::fromResult(o.result);
  // Tracking carries the registration's error to every frame: a result the
  // registration itself flagged is no start for navigation.
  if (!start.failureReason.empty() && !o.allowFlagged)
  {
    throw Error("refusing to track from a result flagged as a failure (" + start.failureReason +
      "): every tracked pose would carry its error; pass --allow-flagged to track anyway");
  }
  const FrameSequence sequence = FrameSequence::load(o.frames);
  // The frames as the registration saw them: undistorted with the lens of
  // the intrinsics file (the one given to `register`), or as they are.
  std::vector<cv::Mat> undistorted;
  if (!o.intrinsics.empty())
  {
    undistorted =
      idealFrames(sequence, readIntrinsics(o.intrinsics), o.frames, o.intrinsics, &std::cerr);
  }
  auto frame = [&](int i) -> const cv::Mat&
  { return undistorted.empty() ? sequence.frame(i) : undistorted[static_cast<std::size_t>(i)]; };
  // By default tracking goes on after the frame the registration ended on.
  int first = o.from;
  if (first < 0)
  {
    first = 0;
    for (int i = 0; i < sequence.size(); ++i)
    {
      if (!start.frameSource.empty() && sequence.name(i) == start.frameSource)
      {
        first = i + 1;
      }
    }
  }
  if (first >= sequence.size())
  {
    throw Error(formatText("no frames to track: '%s' has %d frames, and tracking would start at "
                           "frame %d (after the registered frame '%s'; --from sets it)",
      o.frames.c_str(), sequence.size(), first, start.frameSource.c_str()));
  }
  std::map<int, CameraPose> truth;
  if (!o.truth.empty())
  {
    for (const FramePose& p : readFramePoses(o.truth))
    {
      truth[p.frameId] = p.cameraToWorld;
    }
  }

  // The field stop, found on the frames to track as register finds it by default.
  std::vector<cv::Mat> pictures;
  for (int i = first; i < sequence.size(); ++i)
  {
    pictures.push_back(frame(i));
  }
  const FieldOfView view = FieldOfView::ofSequence(pictures, FieldOfViewOptions());
  EndoscopeTracker tracker(start.modelCT, start.intrinsics, o.tracker);
  tracker.start(start.frame, start.cameraToCT, view.mask());
  std::unique_ptr<LivePoseStream> stream;
  if (o.serve)
  {
    stream = std::make_unique<LivePoseStream>(o.server, "vimlop track");
    if (o.waitForClientS > 0.0 && !stream->waitForClient(o.waitForClientS))
    {
      std::cerr << formatText("vimlop: warning: no client connected within %g s "
                              "(--wait-for-client-s); tracking starts anyway\n",
        o.waitForClientS);
    }
  }
  std::vector<FramePose> poses;
  nlohmann::json records = nlohmann::json::array();
  std::vector<double> latency, errorMm;
  int counts[3] = { 0, 0, 0 };
  for (int i = first; i < sequence.size(); ++i)
  {
    const TrackedFrame t = tracker.track(frame(i));
    const int id = sequence.ids()[static_cast<std::size_t>(i)];
    ++counts[static_cast<int>(t.state)];
    latency.push_back(t.latencyMs);
    nlohmann::json record = { { "frame_id", id }, { "source", sequence.name(i) },
      { "state", toString(t.state) }, { "tracked_features", t.trackedFeatures },
      { "inliers", t.inliers }, { "reprojection_error_px", t.reprojectionErrorPx },
      { "new_features", t.newFeatures }, { "latency_ms", t.latencyMs } };
    const auto known = truth.find(id);
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
      poses.push_back({ id, t.cameraToCT });
    }
    if (stream && t.state == TrackingState::Lost)
    {
      stream->sendLost(id, t.reason);
    }
    else if (stream)
    {
      stream->sendPose(poses.back(), t.reason);
    }
  }
  if (stream && !stream->finish(5.0))
  {
    std::cerr << "vimlop: warning: a client had not taken every pose 5 s after the last frame\n";
  }

  fs::create_directories(o.out);
  // Lost frames have no pose a navigation system should show: they are in
  // tracking.json with their state, not in the pose file.
  writeFramePoses(poses, (fs::path(o.out) / "tracked-poses.json").string());
  const Summary latencyMs = summarize(latency);
  nlohmann::json report = { { "result", o.result }, { "frames", o.frames },
    { "start_frame_id", start.frameId }, { "first_tracked_index", first },
    { "tracking", counts[0] }, { "degraded", counts[1] }, { "lost", counts[2] },
    { "latency_ms", { { "median", latencyMs.median }, { "p99", latencyMs.p99 } } },
    { "per_frame", records } };
  CommandSummary summary;
  summary.lines.push_back(formatText("vimlop track: %zu frames from '%s': %d tracking, %d "
                                     "degraded, %d lost; latency %.1f ms median, %.1f ms p99",
    records.size(), sequence.name(first).c_str(), counts[0], counts[1], counts[2], latencyMs.median,
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
  summary.lines.push_back(
    "wrote '" + (fs::path(o.out) / "tracked-poses.json").string() + "' and tracking.json");
  summary.json = report;
  summary.json.erase("per_frame");
  printSummary(summary, o.json);
}

} // namespace

void addTrackCommand(CLI::App& app)
{
  auto o = std::make_shared<TrackOptions>();
  CLI::App* c = app.add_subcommand("track",
    "Follow the endoscope frame by frame after a registration (issue 16): from the last frame a "
    "result folder registered, the pose of every later frame in the CT, with its state "
    "(tracking, degraded, lost); OUT/tracked-poses.json and OUT/tracking.json");
  c->add_option("--result", o->result, "result folder of vimlop register")->required();
  c->add_option("--frames", o->frames,
     "the frames to track: a folder of frames, a video file or a tracked sequence")
    ->required();
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
  c->add_option("--inlier-px", o->tracker.inlierThresholdPx,
     "a feature agrees with a pose within this reprojection error, px")
    ->capture_default_str();
  addJsonFlag(*c, o->json);
  c->callback([o] { runTrack(*o); });
}

} // namespace vimlop
