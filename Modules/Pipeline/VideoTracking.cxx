#include <vimlop/Pipeline/VideoTracking.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Core/VisibleModelContours.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Pipeline/FrameContourCheck.h>
#include <vimlop/Pipeline/TrackedVideoWriter.h>
#include <vimlop/Pipeline/TrackerLag.h>
#include <vimlop/Pipeline/TrackerRecording.h>
#include <vimlop/Pipeline/TrackingStart.h>
#include <vimlop/Pipeline/TrackingSupervisor.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Results/TrackedPoseTable.h>
#include <vimlop/Video/FrameStream.h>
#include <vimlop/Video/FrameUndistorter.h>
#include <vimlop/Video/IntrinsicsIO.h>
#include <vimlop/Video/VideoInput.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>

namespace vimlop
{

void VideoTrackingOptions::validate() const
{
  this->tracker.validate();
  this->trackerLag.validate();
  this->refinement.validate();
  this->relocalisation.validate();
  if (this->firstFrameIndex < -1)
  {
    throw Error(formatText(
      "the first frame index must be >= 0, or -1 for the one after the registered frame, not %d",
      this->firstFrameIndex));
  }
  if (!std::isfinite(this->videoFps) || this->videoFps <= 0.0)
  {
    throw Error(
      formatText("the tracked video's rate must be a finite number > 0 frames per second, not %g",
        this->videoFps));
  }
}

struct VideoTracking::Internals
{
  VideoTrackingOptions options;
  VideoTrackingInputs inputs;
  std::function<void(const TrackedVideoFrame&)> handler;
  std::function<bool()> stopRequest;
  std::unique_ptr<TrackingStart> start;
  std::optional<FrameUndistorter> undistorter;
  std::optional<FrameStream> stream;
  std::unique_ptr<EndoscopeTracker> tracker;
  /// The registered model, shared by the contour check and the tracked video.
  std::optional<RegistrationModel> model;
  std::unique_ptr<FrameContourCheck> contourCheck;
  std::unique_ptr<TrackingSupervisor> supervisor;
  /// The electromagnetic tracker's recording, and it read in the CT at
  /// each frame's time plus the lag the video measures (which holds the
  /// recording by reference, so is made after it).
  std::optional<TrackerTrajectory> emRecording;
  std::optional<TrackerLag> emTracker;
  /// The id of the stream's first frame, time timeOffsetS on the tracker's clock.
  std::optional<int> firstId;
  /// Frames outside the tracker's recording, tracked without its tip.
  int framesWithoutTip = 0;
  /// What reading the recording dropped (rows, glitches).
  std::vector<std::string> trackerWarnings;
  std::map<int, CameraPose> truth;
  int first = 0;
  int seen = 0;
  std::vector<TrackedVideoFrame> frames;
  std::string stoppedBy;
  bool stopRequested = false;

  bool stopAsked() const { return this->stopRequest && this->stopRequest(); }

  /// The frame's time on the tracker's clock: its own timestamp when its
  /// source records one (a tracked sequence, whose tracker is on the same
  /// clock), else its place at the video's rate; plus the time offset
  /// either way.
  double trackerTimeS(const StreamedFrame& frame) const
  {
    return frame.timestampS
      ? *frame.timestampS + this->inputs.timeOffsetS
      : frameTimeS(frame.id, *this->firstId, this->options.videoFps, this->inputs.timeOffsetS);
  }
  /// What the tracker says at the frame's time (and its lag), in the CT:
  /// its tip, and the camera's rotation when the recording has the
  /// sensor's; none without a tracker, or outside its recording.
  std::optional<TrackerPrior> priorAt(const StreamedFrame& frame)
  {
    if (!this->emTracker)
    {
      return std::nullopt;
    }
    std::optional<TrackerPrior> prior = this->emTracker->priorAt(this->trackerTimeS(frame));
    this->framesWithoutTip += prior ? 0 : 1;
    return prior;
  }
  void writeOutputs(const nlohmann::json& report) const;
};

namespace
{

double elapsedMs(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
    .count();
}

/// The camera the frames are undistorted with: the intrinsics file's lens
/// around the camera the result registered with, which it must be.
PinholeCamera lensOf(const std::string& intrinsicsPath, const PinholeCamera& registered)
{
  if (intrinsicsPath.empty())
  {
    return registered;
  }
  const PinholeCamera given = readIntrinsics(intrinsicsPath);
  const PinholeCamera pinhole = FrameUndistorter(given).pinhole();
  const auto same = [](double a, double b)
  { return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(b)); };
  if (pinhole.widthPx != registered.widthPx || pinhole.heightPx != registered.heightPx ||
    !same(pinhole.fx, registered.fx) || !same(pinhole.fy, registered.fy) ||
    !same(pinhole.cx, registered.cx) || !same(pinhole.cy, registered.cy))
  {
    throwFileError(intrinsicsPath,
      formatText("a %dx%d camera with fx %g, fy %g, cx %g, cy %g, but the result registered a "
                 "%dx%d camera with fx %g, fy %g, cx %g, cy %g: give the intrinsics the result "
                 "was registered with",
        pinhole.widthPx, pinhole.heightPx, pinhole.fx, pinhole.fy, pinhole.cx, pinhole.cy,
        registered.widthPx, registered.heightPx, registered.fx, registered.fy, registered.cx,
        registered.cy));
  }
  return given;
}

} // namespace

VideoTracking::VideoTracking(const VideoTrackingOptions& options)
  : d(std::make_unique<Internals>())
{
  d->options = options;
}

VideoTracking::~VideoTracking() = default;

void VideoTracking::setFrameHandler(std::function<void(const TrackedVideoFrame&)> handler)
{
  d->handler = std::move(handler);
}

void VideoTracking::setStopRequest(std::function<bool()> stopRequested)
{
  d->stopRequest = std::move(stopRequested);
}

void VideoTracking::open(const VideoTrackingInputs& inputs)
{
  d->options.validate();
  if (inputs.framesPath.empty() == (inputs.cameraIndex < 0))
  {
    throw Error("give exactly one of a frame path and a camera index");
  }
  const bool withTracker = !inputs.trackerPath.empty() || !inputs.trackerTransform.empty();
  if (withTracker && inputs.trackerToCTPath.empty())
  {
    throw Error("a tracker's positions are in its own frame: give the tracker registered to the "
                "CT (--tracker-to-ct) to use them");
  }
  if (!withTracker && !inputs.trackerToCTPath.empty())
  {
    throwFileError(
      inputs.trackerToCTPath, "a tracker registered to the CT, but no tracker (--tracker)");
  }
  auto start = std::make_unique<TrackingStart>(TrackingStart::fromResult(inputs.resultFolder));
  // Tracking carries the registration's error to every frame: a result the
  // registration itself flagged is no start for navigation.
  if (!start->failureReason.empty() && !d->options.allowFlagged)
  {
    throw Error("refusing to track from a result flagged as a failure (" + start->failureReason +
      "): every tracked pose would carry its error; pass --allow-flagged to track anyway");
  }
  // The frames as the registration saw them: undistorted with the lens of
  // the intrinsics file (the one given to `register`), or as they are.
  d->undistorter.emplace(lensOf(inputs.intrinsicsPath, start->intrinsics));
  // The tracker's small files before the frames.
  d->trackerWarnings.clear();
  d->emTracker.reset();
  d->emRecording = readTrackerRecording(inputs.trackerPath, inputs.trackerTransform,
    inputs.framesPath, [&](const std::string& warning) { d->trackerWarnings.push_back(warning); });
  if (d->emRecording)
  {
    d->emTracker.emplace(
      *d->emRecording, readTrackerToCT(inputs.trackerToCTPath), d->options.trackerLag);
  }
  d->firstId.reset();
  d->framesWithoutTip = 0;
  d->stream.emplace(inputs.cameraIndex >= 0 ? FrameStream::openCamera(inputs.cameraIndex)
                                            : FrameStream::open(inputs.framesPath));
  // By default tracking goes on after the frame the registration ended on.
  const std::optional<int> registeredAt =
    start->frameSource.empty() ? std::nullopt : d->stream->indexOfName(start->frameSource);
  d->first = d->options.firstFrameIndex >= 0 ? d->options.firstFrameIndex
    : registeredAt                           ? *registeredAt + 1
                                             : 0;
  d->truth.clear();
  if (!inputs.truthPath.empty())
  {
    for (const FramePose& p : readFramePoses(inputs.truthPath))
    {
      d->truth[p.frameId] = p.cameraToWorld;
    }
  }
  d->tracker =
    std::make_unique<EndoscopeTracker>(start->modelCT, start->intrinsics, d->options.tracker);
  d->tracker->start(start->frame, start->cameraToCT, start->fieldOfViewMask);
  // One model for the check and the video, built only when one of them needs it.
  d->model.reset();
  if (d->options.checkContours || (d->options.writeVideo && !inputs.outputFolder.empty()))
  {
    d->model.emplace(makeEmbreeRegistrationModel(start->modelCT));
  }
  d->contourCheck = d->options.checkContours
    ? std::make_unique<FrameContourCheck>(*d->model, start->intrinsics, start->fieldOfViewMask)
    : nullptr;
  d->supervisor = d->contourCheck
    ? std::make_unique<TrackingSupervisor>(*d->contourCheck,
        d->options.refineAgainstCT ? std::optional(d->options.refinement) : std::nullopt,
        d->options.relocalise, d->options.relocalisation, start->contourErrorPx)
    : nullptr;
  d->start = std::move(start);
  d->inputs = inputs;
  d->frames.clear();
  d->stoppedBy.clear();
  d->stopRequested = false;
  d->seen = 0;
}

void VideoTracking::run()
{
  namespace fs = std::filesystem;
  if (!d->tracker)
  {
    throw Error("VideoTracking::run() before open()");
  }
  const TrackingStart& start = *d->start;
  const std::string& out = d->inputs.outputFolder;
  if (!out.empty())
  {
    fs::create_directories(out);
  }
  // The tracked video is written as the frames come, after each pose is sent.
  std::unique_ptr<TrackedVideoWriter> video;
  if (!out.empty() && d->options.writeVideo)
  {
    video = std::make_unique<TrackedVideoWriter>(
      start.intrinsics, (fs::path(out) / "tracked-video.avi").string(), d->options.videoFps);
  }
  StreamedFrame f;
  try
  {
    for (; !(d->stopRequested = d->stopAsked()) && d->stream->next(f); ++d->seen)
    {
      if (!d->firstId)
      {
        d->firstId = f.id;
      }
      if (f.index < d->first)
      {
        continue;
      }
      if (f.image.size() != cv::Size(start.intrinsics.widthPx, start.intrinsics.heightPx))
      {
        throw Error(formatText("frame '%s' of %s is %dx%d pixels, but the result's camera is "
                               "%dx%d: these are not the frames it registered",
          f.name.c_str(), d->stream->source().c_str(), f.image.cols, f.image.rows,
          start.intrinsics.widthPx, start.intrinsics.heightPx));
      }
      // The latency is the whole way from the decoded frame to its pose
      // (sent, when the handler sends it): undistortion, tracking, handler.
      const auto decoded = std::chrono::steady_clock::now();
      const cv::Mat ideal = d->undistorter->undistort(f.image);
      TrackedVideoFrame frame;
      frame.frameId = f.id;
      frame.source = f.name;
      frame.tracked = d->tracker->track(ideal, d->priorAt(f));
      // The check against the CT judges the pose before it is handed on.
      FrameContourAgreement agreement;
      if (d->supervisor)
      {
        const auto checked = std::chrono::steady_clock::now();
        agreement = d->supervisor->judge(ideal, frame.tracked);
        frame.checkMs = elapsedMs(checked);
      }
      const auto known = d->truth.find(f.id);
      if (known != d->truth.end())
      {
        frame.positionErrorMm = cameraPositionError(frame.tracked.cameraToCT, known->second);
        frame.angleErrorDeg = cameraAngleErrorDeg(frame.tracked.cameraToCT, known->second);
      }
      if (d->handler)
      {
        d->handler(frame);
      }
      frame.latencyMs = elapsedMs(decoded);
      // The refinement or relocalisation and the video come after the pose
      // is handed on: they do not add to its latency.
      std::vector<ModelContourPoint> modelContours;
      if (d->supervisor)
      {
        const auto followed = std::chrono::steady_clock::now();
        const CheckedTrackedFrame c = d->supervisor->follow(*d->tracker, frame.tracked, agreement);
        frame.checkMs += elapsedMs(followed);
        frame.contourErrorPx = agreement.medianErrorPx;
        frame.contourPointsDetected = agreement.detected;
        frame.contourPointsMatched = agreement.matched;
        frame.correctionMm = c.correctionMm;
        frame.searched = c.searched;
        frame.relocalised = c.relocalised;
        modelContours = std::move(agreement.modelContours);
      }
      else if (video)
      {
        modelContours = visibleModelContours(*d->model, start.intrinsics, frame.tracked.cameraToCT);
      }
      if (d->emTracker)
      {
        // The frame as finally judged teaches the tracker's lag.
        d->emTracker->learn(d->trackerTimeS(f), frame.tracked);
      }
      d->frames.push_back(frame);
      if (video)
      {
        video->write(ideal, frame.tracked, f.name, modelContours, frame.contourErrorPx);
      }
    }
  }
  catch (const Error& e)
  {
    // The frames tracked before it are written all the same. (A camera or
    // decoder may fail because of the stop itself: that is no error.)
    d->stopRequested = d->stopRequested || d->stopAsked();
    d->stoppedBy = d->stopRequested ? std::string() : e.what();
  }
  if (d->frames.empty() && !d->stoppedBy.empty())
  {
    throw Error(d->stoppedBy);
  }
  if (d->frames.empty() && !d->stopRequested)
  {
    throw Error(formatText("no frames to track: '%s' has %d frames, and tracking would start at "
                           "frame %d (after the registered frame '%s'; --from sets it)",
      d->stream->source().c_str(), d->seen, d->first, start.frameSource.c_str()));
  }
  video.reset();
  if (!out.empty())
  {
    d->writeOutputs(this->report());
  }
}

void VideoTracking::Internals::writeOutputs(const nlohmann::json& report) const
{
  namespace fs = std::filesystem;
  const fs::path out = this->inputs.outputFolder;
  // Lost frames have no pose a navigation system should show: they are in
  // tracking.json with their state, not in the pose file.
  std::vector<FramePose> poses;
  std::vector<TrackedPoseRow> rows;
  for (const TrackedVideoFrame& f : this->frames)
  {
    if (f.tracked.state != TrackingState::Lost)
    {
      poses.push_back({ f.frameId, f.tracked.cameraToCT });
    }
    rows.push_back({ { f.frameId, f.tracked.cameraToCT }, toString(f.tracked.state), f.latencyMs });
  }
  writeFramePoses(poses, (out / "tracked-poses.json").string());
  // Every frame, with its state, for VTK pipelines.
  writeTrackedPoseTable(rows, (out / "tracked-poses.vtt").string());
  writeFileAtomically((out / "tracking.json").string(), report.dump(2) + "\n");
}

const TrackingStart& VideoTracking::start() const
{
  if (!d->start)
  {
    throw Error("VideoTracking::start() before open()");
  }
  return *d->start;
}

const std::string& VideoTracking::source() const
{
  static const std::string none;
  return d->stream ? d->stream->source() : none;
}

int VideoTracking::firstFrameIndex() const
{
  return d->first;
}

const std::vector<TrackedVideoFrame>& VideoTracking::frames() const
{
  return d->frames;
}

int VideoTracking::count(TrackingState state) const
{
  int n = 0;
  for (const TrackedVideoFrame& f : d->frames)
  {
    n += f.tracked.state == state ? 1 : 0;
  }
  return n;
}

Summary VideoTracking::latencyMs() const
{
  std::vector<double> latency;
  for (const TrackedVideoFrame& f : d->frames)
  {
    latency.push_back(f.latencyMs);
  }
  return summarize(latency);
}

const std::string& VideoTracking::stoppedBy() const
{
  return d->stoppedBy;
}

bool VideoTracking::stopRequested() const
{
  return d->stopRequested;
}

nlohmann::json VideoTracking::report() const
{
  nlohmann::json records = nlohmann::json::array();
  std::vector<double> errorMm, contourPx, checkMs;
  for (const TrackedVideoFrame& f : d->frames)
  {
    const TrackedFrame& t = f.tracked;
    nlohmann::json record = { { "frame_id", f.frameId }, { "source", f.source },
      { "state", toString(t.state) }, { "tracked_features", t.trackedFeatures },
      { "inliers", t.inliers }, { "reprojection_error_px", t.reprojectionErrorPx },
      { "new_features", t.newFeatures } };
    if (f.positionErrorMm)
    {
      record["camera_position_error_mm"] = *f.positionErrorMm;
      record["camera_angle_error_deg"] = *f.angleErrorDeg;
      if (t.state != TrackingState::Lost)
      {
        errorMm.push_back(*f.positionErrorMm);
      }
    }
    if (!t.reason.empty())
    {
      record["reason"] = t.reason;
    }
    if (std::isfinite(f.contourErrorPx))
    {
      record["contour_error_px"] = f.contourErrorPx;
      contourPx.push_back(f.contourErrorPx);
    }
    if (f.correctionMm > 0.0)
    {
      record["correction_mm"] = f.correctionMm;
    }
    if (f.searched)
    {
      record["relocalisation"] = f.relocalised ? "found" : "not found";
    }
    if (d->contourCheck)
    {
      record["contour_points"] = { { "detected", f.contourPointsDetected },
        { "matched", f.contourPointsMatched } };
    }
    if (t.tipDistanceMm)
    {
      record["tip_distance_mm"] = *t.tipDistanceMm;
    }
    if (t.trackerTurnDeg)
    {
      record["tracker_turn_deg"] = *t.trackerTurnDeg;
    }
    record["latency_ms"] = f.latencyMs;
    if (d->contourCheck)
    {
      record["check_ms"] = f.checkMs;
      checkMs.push_back(f.checkMs);
    }
    records.push_back(record);
  }
  const Summary latency = this->latencyMs();
  int searched = 0;
  int relocalised = 0;
  for (const TrackedVideoFrame& f : d->frames)
  {
    searched += f.searched ? 1 : 0;
    relocalised += f.relocalised ? 1 : 0;
  }
  nlohmann::json report = { { "result", d->inputs.resultFolder }, { "frames", this->source() },
    { "start_frame_id", d->start ? d->start->frameId : 0 }, { "first_tracked_index", d->first },
    { "tracking", this->count(TrackingState::Tracking) },
    { "degraded", this->count(TrackingState::Degraded) },
    { "lost", this->count(TrackingState::Lost) },
    { "relocalisations", { { "searched", searched }, { "found", relocalised } } },
    { "latency_ms", { { "median", latency.median }, { "p99", latency.p99 } } },
    { "per_frame", records } };
  if (!errorMm.empty())
  {
    const Summary e = summarize(errorMm);
    report["camera_position_error_mm"] = { { "mean", e.mean }, { "max", e.max } };
  }
  if (!contourPx.empty())
  {
    // Each frame's median contour error, over the frames checked.
    const Summary c = summarize(contourPx);
    report["contour_error_px"] = { { "median", c.median }, { "p95", c.p95 }, { "max", c.max } };
    const Summary t = summarize(checkMs);
    report["check_ms"] = { { "median", t.median }, { "p99", t.p99 } };
  }
  if (d->emTracker)
  {
    report["tracker"] = {
      { "recording", d->inputs.trackerPath.empty() ? d->inputs.framesPath : d->inputs.trackerPath },
      { "tracker_to_ct", d->inputs.trackerToCTPath },
      { "rotation", d->emRecording->hasRotations() }, { "frames_without_tip", d->framesWithoutTip },
      { "warnings", d->trackerWarnings }
    };
    if (d->tracker)
    {
      // What the video anchored to the CT saw of the tracker's error: its
      // registration to the patient, as far as this run could tell.
      const TrackerOffset& offset = d->tracker->trackerOffset();
      const Eigen::Vector3d& shift = offset.shiftMm();
      report["tracker"]["offset"] = { { "frames_learned", offset.framesLearned() },
        { "shift_mm", { shift.x(), shift.y(), shift.z() } }, { "turn_deg", offset.turnDeg() } };
    }
    // The lag the video measured, which the recording was read with from
    // its estimate on (none: no estimate was made, or none showed a lag).
    const std::optional<TrackerLagEstimate>& lag = d->emTracker->estimate();
    report["tracker"]["lag"] = lag ? nlohmann::json{ { "lag_s", lag->lagS },
      { "pairs", lag->pairs }, { "disagreement_mm", lag->disagreementMm },
      { "disagreement_at_zero_mm", lag->disagreementAtZeroMm } }
                                   : nlohmann::json();
  }
  if (!d->stoppedBy.empty() || d->stopRequested)
  {
    report["stopped_by"] =
      d->stopRequested ? "interrupted (Ctrl-C, SIGTERM or AbortExecute)" : d->stoppedBy;
  }
  return report;
}

} // namespace vimlop
