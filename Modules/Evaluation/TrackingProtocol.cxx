#include <vimlop/Evaluation/TrackingProtocol.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/MultiStartRegistration.h>
#include <vimlop/Core/Registration.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/SimulatedVideoCase.h>
#include <vimlop/Evaluation/SimulatedWorld.h>
#include <vimlop/Pipeline/FrameContourCheck.h>
#include <vimlop/Pipeline/TrackerLag.h>
#include <vimlop/Pipeline/TrackingSupervisor.h>
#include <vimlop/Pipeline/VideoRegistrationPipeline.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Video/FrameUndistorter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

namespace vimlop
{

namespace
{

nlohmann::json summaryJson(const Summary& s)
{
  return { { "mean", s.mean }, { "median", s.median }, { "p95", s.p95 }, { "p99", s.p99 },
    { "max", s.max } };
}

double meanOf(
  const std::vector<TrackingProtocolFrame>& frames, std::size_t first, std::size_t count)
{
  double sum = 0.0;
  for (std::size_t i = first; i < first + count; ++i)
  {
    sum += frames[i].positionErrorMm;
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

/// The registration of the first frames: P2's, on the sequence's beginning.
VideoProtocolOptions registrationOf(const TrackingProtocolOptions& o)
{
  VideoProtocolOptions registration = o.registration;
  registration.simulation = o.simulation;
  registration.simulation.frames = o.registrationFrames;
  return registration;
}

} // namespace

EndoscopeSimulationOptions TrackingProtocolOptions::defaultSimulation()
{
  EndoscopeSimulationOptions s;
  s.frames = 600;
  s.replay.pathFrames = 48;
  s.replay.leadFrames = 30;
  return s;
}

void TrackingProtocolOptions::validate() const
{
  this->simulation.validate();
  if (this->registrationFrames < 3 || this->registrationFrames >= this->simulation.frames)
  {
    throw Error(formatText("evaluate tracking: %d frames registered of %d: at least 3, and fewer "
                           "than the sequence has",
      this->registrationFrames, this->simulation.frames));
  }
  if (this->simulation.replay.leadFrames < this->registrationFrames)
  {
    throw Error(formatText("evaluate tracking: the sequence must lead straight in over the %d "
                           "frames registered (SfM needs their parallax), not %d",
      this->registrationFrames, this->simulation.replay.leadFrames));
  }
  registrationOf(*this).validate();
  this->tracker.validate();
  this->trackerLag.validate();
  if (!(this->flagErrorMm > 0.0))
  {
    throw Error(formatText(
      "evaluate tracking: the error to flag must be positive, not %g mm", this->flagErrorMm));
  }
  if (this->driftFrames < 1)
  {
    throw Error(
      formatText("evaluate tracking: the drift needs at least 1 frame at each end, not %d",
        this->driftFrames));
  }
}

nlohmann::json TrackingProtocolReport::toJson() const
{
  nlohmann::json frames = nlohmann::json::array();
  for (const TrackingProtocolFrame& f : this->perFrame)
  {
    frames.push_back({ { "frame", f.frame }, { "state", f.state },
      { "camera_position_mm", f.positionErrorMm }, { "camera_angle_deg", f.angleErrorDeg },
      { "tracked_features", f.trackedFeatures }, { "inliers", f.inliers },
      { "reprojection_error_px", f.reprojectionErrorPx }, { "latency_ms", f.latencyMs } });
    if (std::isfinite(f.contourErrorPx))
    {
      frames.back()["contour_error_px"] = f.contourErrorPx;
    }
    if (f.correctionMm > 0.0)
    {
      frames.back()["correction_mm"] = f.correctionMm;
    }
    if (f.searched)
    {
      frames.back()["relocalisation"] = f.relocalised ? "found" : "not found";
      frames.back()["relocalisation_ms"] = f.searchMs;
    }
  }
  return { { "protocol", "tracking" }, { "frames", this->frames }, { "seed", this->seed },
    { "registration",
      { { "frames", this->registrationFrames }, { "camera_position_mm", this->registrationErrorMm },
        { "runtime_s", this->registrationSeconds },
        { "contour_error_px", this->registrationContourErrorPx },
        { "flagged", !this->registrationFailure.empty() },
        { "failure_reason", this->registrationFailure } } },
    { "start_frame", this->startFrame }, { "tracker_prior", this->trackerPrior },
    { "tracker_rotation", this->trackerRotation },
    { "tracker_offset",
      { { "frames_learned", this->trackerOffsetFramesLearned },
        { "shift_mm", this->trackerOffsetShiftMm }, { "turn_deg", this->trackerOffsetTurnDeg } } },
    { "tracker_lag", { { "lag_s", this->trackerLagS }, { "pairs", this->trackerLagPairs } } },
    { "latency_ms", summaryJson(this->latencyMs) },
    { "camera_position_mm", summaryJson(this->positionErrorMm) },
    { "camera_angle_deg", summaryJson(this->angleErrorDeg) }, { "drift_mm", this->driftMm },
    { "tracked_fraction", this->trackedFraction }, { "degraded_frames", this->degradedFrames },
    { "lost_frames", this->lostFrames }, { "corrected_frames", this->correctedFrames },
    { "relocalisations",
      { { "searched", this->relocalisationsSearched }, { "found", this->relocalisationsFound } } },
    { "unflagged_frames_over_2mm", this->unflaggedFramesOverLimit },
    { "flag_error_mm", this->flagErrorMm }, { "per_frame", frames } };
}

std::vector<std::string> TrackingProtocolReport::summaryLines() const
{
  std::vector<std::string> lines{
    formatText("tracking: %d frames, registered on the first %d (camera %.3f mm, %.1f s%s), "
               "tracked from frame %d%s",
      this->frames, this->registrationFrames, this->registrationErrorMm, this->registrationSeconds,
      this->registrationFailure.empty() ? "" : ("; flagged: " + this->registrationFailure).c_str(),
      this->startFrame,
      this->trackerPrior ? (this->trackerRotation ? ", with the tracker's tip and rotation"
                                                  : ", with the tracker's tip")
                         : ""),
    formatText("tracking: camera %.3f mm mean (p95 %.3f, max %.3f), %.3f deg mean; drift %.3f mm",
      this->positionErrorMm.mean, this->positionErrorMm.p95, this->positionErrorMm.max,
      this->angleErrorDeg.mean, this->driftMm),
    formatText("tracking: %d corrections against the CT; %d relocalisations searched, %d found",
      this->correctedFrames, this->relocalisationsSearched, this->relocalisationsFound),
    formatText("tracking: latency %.1f ms median, %.1f ms p99; %.1f %% of frames tracked (%d "
               "degraded, %d lost); %d frames over %.1f mm not flagged",
      this->latencyMs.median, this->latencyMs.p99, 100.0 * this->trackedFraction,
      this->degradedFrames, this->lostFrames, this->unflaggedFramesOverLimit, this->flagErrorMm),
  };
  if (this->trackerPrior)
  {
    lines.push_back(this->trackerLagPairs > 0
        ? formatText("tracking: the tracker's lag, as the video's motion showed it: %.1f ms (%d "
                     "pairs of frames)",
            1000.0 * this->trackerLagS, this->trackerLagPairs)
        : std::string("tracking: the video measured no lag of the tracker"));
  }
  return lines;
}

TrackingProtocolReport runTrackingProtocol(
  const SimulatedWorld& world, const TrackingProtocolOptions& o, const EvaluationProgress& progress)
{
  o.validate();
  auto say = [&](const std::string& text) { reportEvaluationNote(progress, "tracking: " + text); };

  // The registration of the first frames, as P2 does it. The shorter
  // sequence is the long one's beginning: the same path, replayed from the
  // same seed, rendered with the same per-frame noise.
  const VideoProtocolOptions registration = registrationOf(o);
  const auto began = std::chrono::steady_clock::now();
  const SimulatedVideoCase c = prepareSimulatedVideoCase(world, registration, progress);
  const RegistrationModel& model = c.pipeline->model();
  std::mt19937_64 rng(o.simulation.seed * 2654435761ull + 99ull);
  const SimilarityTransform start = perturbedStart(c, model, rng, registration.perturbMinMm,
    registration.perturbMaxMm, registration.perturbMinDeg, registration.perturbMaxDeg);
  const RegistrationResult registered =
    registerVideo(model, c.data, start, registration.pipeline.registrationOptions(c.initialScale));
  TrackingProtocolReport report;
  report.frames = o.simulation.frames;
  report.seed = o.simulation.seed;
  report.registrationFrames = o.registrationFrames;
  report.registrationErrorMm = cameraErrors(c, registered.sfmToCT, 0.0).positionMeanMm;
  report.registrationSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  report.flagErrorMm = o.flagErrorMm;
  report.registrationFailure = failureReason(registered, registration.pipeline.multiStart);
  report.registrationContourErrorPx = registered.contourErrorPx;
  // Tracking starts on the last frame SfM registered.
  const auto last = std::max_element(c.frameOf.begin(), c.frameOf.end());
  const std::size_t lastData = static_cast<std::size_t>(last - c.frameOf.begin());
  report.startFrame = *last;
  report.trackerPrior = o.trackerPrior;
  report.trackerRotation = o.trackerPrior && o.simulation.trackerRotation;
  const CameraPose startPose = registered.sfmToCT.apply(c.data.frames[lastData].cameraToSfm);
  say(formatText("registered %d frames: camera %.3f mm; tracking from frame %d",
    o.registrationFrames, report.registrationErrorMm, report.startFrame));

  // The whole sequence, from the same truth.
  const RegistrationModel truth = makeEmbreeRegistrationModel(world.truth);
  const SimulatedVideo video = simulateEndoscopeVideo(truth, o.simulation, progress);
  // Each frame undistorted once, with the intrinsics the user has, for the
  // tracker and the check against the CT, as vimlop track does.
  const FrameUndistorter undistorter(video.calibratedIntrinsics);
  EndoscopeTracker tracker(world.model, undistorter.pinhole(), o.tracker);
  tracker.start(undistorter.undistort(video.frames[static_cast<std::size_t>(report.startFrame)]),
    startPose, c.pipeline->fieldOfViewMask());
  const FrameContourCheck contourCheck(
    makeEmbreeRegistrationModel(world.model), undistorter.pinhole(), c.pipeline->fieldOfViewMask());
  TrackingSupervisor supervisor(contourCheck,
    o.refineAgainstCT ? std::optional(o.refinement) : std::nullopt, o.relocalise, o.relocalisation,
    registered.contourErrorPx);
  // The simulated tracker records in the CT frame.
  std::optional<TrackerLag> emTracker;
  if (o.trackerPrior)
  {
    emTracker.emplace(video.tracker, Eigen::Matrix4d::Identity(), o.trackerLag);
  }
  std::vector<double> latency, position, angle;
  for (int f = report.startFrame + 1; f < o.simulation.frames; ++f)
  {
    // The latency runs from the decoded frame to the judged pose, as in
    // vimlop track: undistortion, tracking and the check against the CT.
    const auto decoded = std::chrono::steady_clock::now();
    const cv::Mat ideal = undistorter.undistort(video.frames[static_cast<std::size_t>(f)]);
    const double timeS = video.frameTimesS[static_cast<std::size_t>(f)];
    TrackedFrame t = tracker.track(ideal, emTracker ? emTracker->priorAt(timeS) : std::nullopt);
    const FrameContourAgreement agreement = supervisor.judge(ideal, t);
    t.latencyMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - decoded).count();
    TrackingProtocolFrame r;
    r.frame = f;
    r.state = toString(t.state);
    r.positionErrorMm =
      cameraPositionError(t.cameraToCT, video.camerasCT[static_cast<std::size_t>(f)]);
    r.angleErrorDeg =
      cameraAngleErrorDeg(t.cameraToCT, video.camerasCT[static_cast<std::size_t>(f)]);
    r.trackedFeatures = t.trackedFeatures;
    r.inliers = t.inliers;
    r.reprojectionErrorPx = t.reprojectionErrorPx;
    r.latencyMs = t.latencyMs;
    const CheckedTrackedFrame checked = supervisor.follow(tracker, t, agreement);
    r.contourErrorPx = agreement.medianErrorPx;
    r.correctionMm = checked.correctionMm;
    r.searched = checked.searched;
    r.relocalised = checked.relocalised;
    r.searchMs = checked.searchMs;
    if (emTracker)
    {
      emTracker->learn(timeS, t);
    }
    report.correctedFrames += checked.corrected && !checked.relocalised ? 1 : 0;
    report.relocalisationsSearched += checked.searched ? 1 : 0;
    report.relocalisationsFound += checked.relocalised ? 1 : 0;
    report.degradedFrames += t.state == TrackingState::Degraded;
    report.lostFrames += t.state == TrackingState::Lost;
    report.unflaggedFramesOverLimit +=
      t.state == TrackingState::Tracking && r.positionErrorMm > o.flagErrorMm;
    if (t.state != TrackingState::Lost)
    {
      position.push_back(r.positionErrorMm);
      angle.push_back(r.angleErrorDeg);
    }
    latency.push_back(r.latencyMs);
    report.perFrame.push_back(r);
    reportEvaluationCount(progress, "tracking: frame", f - report.startFrame,
      o.simulation.frames - 1 - report.startFrame);
  }
  const std::size_t tracked = report.perFrame.size();
  report.trackerOffsetFramesLearned = tracker.trackerOffset().framesLearned();
  report.trackerOffsetShiftMm = tracker.trackerOffset().shiftMm().norm();
  report.trackerOffsetTurnDeg = tracker.trackerOffset().turnDeg();
  if (emTracker && emTracker->estimate())
  {
    report.trackerLagS = emTracker->lagS();
    report.trackerLagPairs = emTracker->estimate()->pairs;
  }
  report.latencyMs = summarize(latency);
  report.positionErrorMm = summarize(position);
  report.angleErrorDeg = summarize(angle);
  report.trackedFraction = tracked > 0
    ? static_cast<double>(tracked - static_cast<std::size_t>(report.lostFrames)) /
      static_cast<double>(tracked)
    : 0.0;
  const std::size_t ends =
    std::min<std::size_t>(static_cast<std::size_t>(o.driftFrames), tracked / 2);
  report.driftMm = meanOf(report.perFrame, tracked - ends, ends) - meanOf(report.perFrame, 0, ends);
  return report;
}

} // namespace vimlop
