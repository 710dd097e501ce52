#include <vimlop/Pipeline/VideoRegistrationPipeline.h>

#include "VideoRegistrationPipelineInternals.h"
#include <vimlop/Core/CanonicalStarts.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/Registration.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Imaging/ModelLoading.h>
#include <vimlop/Pipeline/TrackerRecording.h>
#include <vimlop/Pipeline/VideoRegistrationData.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Results/InputIdentity.h>
#include <vimlop/Video/FieldOfView.h>
#include <vimlop/Video/FrameContoursIO.h>
#include <vimlop/Video/FrameSequence.h>
#include <vimlop/Video/IntrinsicsIO.h>
#include <vimlop/Video/OccludingContourDetector.h>
#include <vimlop/Video/SfmReconstructionIO.h>
#include <vimlop/Video/TrackerScale.h>
#include <vimlop/Video/VideoInput.h>

#include <Eigen/SVD>

#include <opencv2/core/mat.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <ostream>
#include <sstream>

namespace vimlop
{

void VideoRegistrationPipeline::loadModel(const TriangleMesh& airwayCT)
{
  Internals& d = *this->Impl;
  const StageTimings::Stopwatch watch;
  d.progress("model", 0.0);
  d.Mesh = airwayCT;
  d.Model = std::make_unique<RegistrationModel>(makeEmbreeRegistrationModel(*d.Mesh));
  d.Timings.set("model", watch);
  d.progress("model", 1.0);
}

void VideoRegistrationPipeline::loadModel(const std::string& meshPath, const std::string& ctPath)
{
  // The model's time includes reading the mesh or segmenting the CT, its longest part.
  const StageTimings::Stopwatch watch;
  this->Impl->say("model");
  std::map<std::string, std::string> identity;
  this->loadModel(airwayMeshFrom(meshPath, ctPath, &identity));
  this->Impl->CTIdentity = std::move(identity);
  this->Impl->Timings.set("model", watch);
}

void VideoRegistrationPipeline::loadFrames(const std::string& path, const PinholeCamera& intrinsics,
  int maxFrames, const std::string& intrinsicsSource)
{
  Internals& d = *this->Impl;
  const StageTimings::Stopwatch watch;
  d.progress("frames", 0.0);
  const FrameSequence sequence = FrameSequence::load(path, maxFrames);
  intrinsics.validate();
  d.Frames = idealFrames(sequence, intrinsics, path, intrinsicsSource, d.Log);
  d.Names = sequence.names();
  d.Ids = sequence.ids();
  d.TimestampsS = sequence.timestampsS();
  d.RecordedFramesPerSecond = sequence.framesPerSecond();
  if (const std::string gaps = sequence.idGaps(); !gaps.empty())
  {
    d.Warn("missing from the frames' numbering: " + gaps +
      "; every frame keeps the number of its file as its id and its time");
  }
  d.Intrinsics = intrinsics;
  d.View = FieldOfView::ofSequence(d.Frames, d.Opts.fieldOfView);
  if (!d.View->isEverything())
  {
    std::ostringstream text;
    text << "field stop (" << fieldStopModeName(d.Opts.fieldOfView.mode)
         << "): " << 100.0 * d.View->validFraction() << " % of the frame used";
    if (d.View->isCircular())
    {
      text << ", circle at (" << d.View->centreUPx() << ", " << d.View->centreVPx()
           << ") px of radius " << d.View->radiusPx() << " px";
    }
    d.say(text.str());
  }
  d.FramesLoaded = true;
  d.Timings.set("frames", watch);
  d.progress("frames", 1.0);
}

void VideoRegistrationPipeline::detectContours()
{
  Internals& d = *this->Impl;
  d.need(d.FramesLoaded, "load the frames");
  const StageTimings::Stopwatch watch;
  d.say("contours of " + std::to_string(d.Frames.size()) + " frames");
  const OccludingContourDetector detector{ d.Opts.contours };
  d.Contours.clear();
  // Every pixel valid: no mask at all, so a sequence without a field stop
  // gives exactly the points it always did.
  const cv::Mat mask = d.View && !d.View->isEverything() ? d.View->mask() : cv::Mat();
  size_t detected = 0;
  size_t dropped = 0;
  for (size_t f = 0; f < d.Frames.size(); ++f)
  {
    d.progress("contours", static_cast<double>(f) / d.Frames.size());
    OccludingContourDetector::MaskedDetectionCounts counts;
    d.Contours.push_back(detector.detect(d.Frames[f], mask, &counts));
    detected += counts.detected;
    dropped += counts.dropped;
  }
  if (!mask.empty())
  {
    d.sayContourPointsDropped(dropped, detected);
  }
  d.ContoursDetected = true;
  d.Timings.set("contours", watch);
  d.progress("contours", 1.0);
}

void VideoRegistrationPipeline::reconstruct(const std::string& colmapFolder)
{
  Internals& d = *this->Impl;
  d.need(d.FramesLoaded, "load the frames");
  const StageTimings::Stopwatch watch;
  d.progress("sfm", 0.0);
  PinholeCamera ideal = d.Intrinsics;
  ideal.removeDistortion();
  const cv::Mat mask = d.View && !d.View->isEverything() ? d.View->mask() : cv::Mat();
  SfmReconstruction sfm = reconstructFrames(
    d.Frames, d.Names, ideal, colmapFolder, d.Opts.registration.threads, d.Log, mask);
  if (sfm.numberOfRegisteredFrames() < 2 || sfm.points.size() < 10)
  {
    throw Error("SfM registered " + std::to_string(sfm.numberOfRegisteredFrames()) +
      " frames and " + std::to_string(sfm.points.size()) + " points; too few to register");
  }
  d.Sfm = std::move(sfm);
  d.Timings.set("sfm", watch);
  d.progress("sfm", 1.0);
}

void VideoRegistrationPipeline::estimateInitialScale(
  const TrackerTrajectory* tracker, double fps, double timeOffsetS, double givenScale)
{
  Internals& d = *this->Impl;
  const SfmReconstruction& sfm = d.need(d.Sfm, "reconstruct");
  const StageTimings::Stopwatch watch;
  if (!tracker && !(givenScale > 0.0))
  {
    throw Error("give a tracker recording or an initial scale: SfM alone has no metric scale");
  }
  d.idsOf(sfm); // SfM kept every loaded frame: the times are the loaded frames'
  d.TimesS = d.frameTimes(fps, timeOffsetS, tracker != nullptr);
  d.GivenFramesPerSecond = fps;
  double scale = givenScale;
  if (tracker)
  {
    const TrackerScaleResult fromTracker = scaleFromTracker(*tracker, sfm, d.TimesS, d.Log);
    if (givenScale > 0.0)
    {
      const double ratio = fromTracker.scale / givenScale;
      if (ratio > d.Opts.scaleBoundFactor || ratio < 1.0 / d.Opts.scaleBoundFactor)
      {
        d.Warn("the tracker's scale " + std::to_string(fromTracker.scale) +
          " disagrees with the given scale " + std::to_string(givenScale) +
          " by more than the scale bound; using the given scale");
      }
    }
    else
    {
      scale = fromTracker.scale;
    }
  }
  d.Scale = scale;
  std::ostringstream text;
  text << "initial scale " << scale << " mm per SfM unit";
  d.say(text.str());
  d.Timings.set("scale", watch);
}

void VideoRegistrationPipeline::makeData()
{
  Internals& d = *this->Impl;
  const SfmReconstruction& sfm = d.need(d.Sfm, "reconstruct");
  d.need(d.ContoursDetected, "detect the contours");
  d.need(d.Scale > 0.0, "estimate the initial scale");
  const StageTimings::Stopwatch watch;
  d.Data = makeVideoRegistrationData(
    sfm, d.Contours, d.Scale, d.Opts.pointNoiseFloorMm, &d.FrameOf, &d.idsOf(sfm));
  d.DataMade = true;
  d.Timings.set("data", watch);
}

std::vector<CameraPose> VideoRegistrationPipeline::Internals::turnedAsTracked(
  const std::vector<CameraPose>& canonical) const
{
  const int frameId = this->Data.frames[canonicalAnchorIndex(this->Data)].frameId;
  const auto at = std::find(this->Ids.begin(), this->Ids.end(), frameId);
  const std::optional<Eigen::Matrix4d> sensor = at == this->Ids.end() || this->TimesS.empty()
    ? std::nullopt
    : this->Tracker->poseAt(this->TimesS[static_cast<size_t>(at - this->Ids.begin())]);
  if (!sensor)
  {
    this->Warn("the tracker has no pose at frame " + std::to_string(frameId) +
      "'s time: the canonical starts keep their own rotations");
    return canonical;
  }
  const Eigen::Matrix4d cameraToCT = *this->TrackerToCT * *sensor;
  // A registration with scale or shear is not a rotation: its nearest one.
  CameraPose tracked;
  tracked.rotation = nearestRotation(cameraToCT.topLeftCorner<3, 3>().eval());
  tracked.centre = cameraToCT.topRightCorner<3, 1>();
  std::vector<CameraPose> poses = vimlop::turnedAsTracked(canonical, tracked);
  const bool inside = this->Model->isInside(tracked.centre);
  if (!inside)
  {
    poses.erase(poses.begin());
  }
  std::ostringstream text;
  text << "rotation prior: frame " << frameId << " turned as the tracker registered to the CT "
       << "says, at " << poses.size() - (inside ? 1 : 0) << " canonical positions"
       << (inside ? " and at its tracked position"
                  : " (its tracked position is outside the airway)");
  this->say(text.str());
  return poses;
}

void VideoRegistrationPipeline::makeCanonicalStarts(
  const std::vector<CameraPose>* posesCT, const std::string& source)
{
  Internals& d = *this->Impl;
  d.need(d.Model != nullptr, "load the model");
  d.need(d.DataMade, "make the data");
  const StageTimings::Stopwatch watch;
  std::vector<CameraPose> poses;
  if (!posesCT)
  {
    CanonicalPoseOptions canonical = d.Opts.canonical;
    canonical.threads = d.Opts.registration.threads;
    poses = makeCanonicalPoses(*d.Model, canonical);
  }
  else
  {
    int dropped = 0;
    for (const CameraPose& p : *posesCT)
    {
      if (d.Model->isInside(p.centre))
      {
        poses.push_back(p);
      }
      else
      {
        ++dropped;
      }
    }
    if (dropped > 0)
    {
      d.Warn(std::to_string(dropped) + " canonical poses" +
        (source.empty() ? std::string() : " of '" + source + "'") +
        " lie outside the patient's airway; dropped");
    }
    if (poses.empty())
    {
      throw Error((source.empty() ? std::string() : "'" + source + "': ") +
        "no canonical pose lies inside the patient's airway");
    }
  }
  if (d.TrackerToCT && d.Tracker)
  {
    poses = d.turnedAsTracked(poses);
  }
  d.Starts = canonicalStarts(d.Data, d.Scale, poses, &d.Anchor);
  d.Mode = StartMode::Canonical;
  d.say(std::to_string(poses.size()) + " canonical poses, frame " + std::to_string(d.Anchor) +
    " placed at each");
  d.Timings.set("starts", watch);
}

void VideoRegistrationPipeline::makeManualStart(const FramePose& pose)
{
  Internals& d = *this->Impl;
  d.need(d.DataMade, "make the data");
  const StageTimings::Stopwatch watch;
  auto it = std::find_if(d.Data.frames.begin(), d.Data.frames.end(),
    [&](const VideoFrame& f) { return f.frameId == pose.frameId; });
  if (it == d.Data.frames.end())
  {
    throw Error("frame " + std::to_string(pose.frameId) +
      " is not a frame SfM registered; give the pose of another frame");
  }
  d.Starts = { startFromCameraPose(pose.cameraToWorld, it->cameraToSfm, d.Scale) };
  d.Mode = StartMode::Manual;
  d.Anchor = pose.frameId;
  d.Timings.set("starts", watch);
}

void VideoRegistrationPipeline::setStarts(
  const std::vector<SimilarityTransform>& startsSfmToCT, StartMode mode)
{
  if (startsSfmToCT.empty())
  {
    throw Error("video registration: no start given");
  }
  this->Impl->Starts = startsSfmToCT;
  this->Impl->Mode = mode;
  this->Impl->Anchor = -1;
}

void VideoRegistrationPipeline::run()
{
  Internals& d = *this->Impl;
  d.need(d.Model != nullptr, "load the model");
  d.need(d.DataMade, "make the data");
  d.need(!d.Starts.empty(), "make the starts");
  // The registration's phases of an earlier run() are replaced by this one's.
  for (const char* phase : { "screening", "final", "registration" })
  {
    d.Timings.remove(phase);
  }
  StageTimings::Stopwatch watch;
  const RegistrationOptions options = d.Opts.registrationOptions(d.Scale);
  MultiStartOptions multi = d.Opts.multiStart;
  multi.registration = options;
  multi.threads = d.Opts.registration.threads;
  if (d.Starts.size() > 1)
  {
    bool screened = false;
    try
    {
      d.Outcome = registerMultiStart(*d.Model, d.Data, d.Starts, multi,
        [&](const char* phase, int done, int total)
        {
          // The screening ends where the final phase starts; the time before
          // the first phase (the screening's subsample) counts to the first.
          const std::string name = phase;
          if (done == 0 && name == "screening")
          {
            screened = true;
          }
          else if (done == 0 && name == "final" && screened)
          {
            d.Timings.set("screening", watch);
            watch = StageTimings::Stopwatch();
          }
          if (d.Log && (done == total || done % 10 == 0))
          {
            *d.Log << "vimlop register: " << phase << " " << done << "/" << total << "\n";
          }
          return !d.Report ||
            d.Report(
              std::string("registration ") + phase, static_cast<double>(done) / std::max(total, 1));
        });
    }
    catch (const Error&)
    {
      d.progress("registration", 1.0); // a cancellation shows as PipelineCancelled
      throw;
    }
    d.Timings.set("final", watch);
    d.warnAtScaleBound();
    d.hintAtRoll();
    return;
  }
  // A single start uses every thread inside the registration instead.
  multi.scaleFactors = { 1.0 };
  MultiStartResult outcome;
  outcome.candidates.resize(1);
  outcome.candidates[0].initialSfmToCT = d.Starts[0];
  const double maxIterations = std::max(options.maxIterations, 1);
  bool cancelled = false;
  outcome.best = registerVideo(*d.Model, d.Data, d.Starts[0], options,
    [&](const IterationRecord& r)
    {
      if (d.Log && r.iteration % 10 == 0)
      {
        *d.Log << "vimlop register: iteration " << r.iteration << ", contour error "
               << r.contourErrorPx << " px\n";
      }
      cancelled = d.Report && !d.Report("registration", r.iteration / maxIterations);
      return !cancelled;
    });
  if (cancelled)
  {
    throw PipelineCancelled{};
  }
  outcome.bestCandidate = 0;
  outcome.flagFailure(multi);
  d.Outcome = std::move(outcome);
  d.Timings.set("registration", watch);
  d.warnAtScaleBound();
}

void VideoRegistrationPipeline::run(const VideoRegistrationInputs& inputs)
{
  this->prepare(inputs);
  this->process();
}

void VideoRegistrationPipeline::prepare(const VideoRegistrationInputs& in)
{
  Internals& d = *this->Impl;
  // The small files first, so that a bad one fails before the long work.
  d.Tracker = readTrackerRecording(in.trackerPath, in.trackerTransform, in.framesPath, d.Warn);
  if (!d.Tracker && !(in.initialScale > 0.0))
  {
    throw Error("give a tracker recording or an initial scale: SfM alone has no metric scale");
  }
  d.TrackerToCT.reset();
  if (!in.trackerToCTPath.empty())
  {
    if (!d.Tracker || !d.Tracker->hasRotations())
    {
      throwFileError(in.trackerToCTPath,
        "a tracker registered to the CT turns the starts only with a 6-DOF sensor's rotation: "
        "a tracked sequence's transform (--tracker-transform) or a tracker CSV with the "
        "columns qw,qx,qy,qz");
    }
    d.TrackerToCT = readTrackerToCT(in.trackerToCTPath);
  }
  d.StartPoses.clear();
  if (!in.startPosesPath.empty())
  {
    d.StartPoses = readFramePoses(in.startPosesPath);
    if (d.StartPoses.empty())
    {
      throwFileError(in.startPosesPath, "holds no pose");
    }
  }
  else if (in.startMode == StartMode::Manual)
  {
    throw Error("a manual start needs a pose file");
  }
  // Earlier stages' outputs are small files too.
  d.GivenSfm.reset();
  d.GivenContours.reset();
  if (!in.sfmFile.empty())
  {
    d.GivenSfm = readSfmReconstruction(in.sfmFile);
  }
  if (!in.contoursFile.empty())
  {
    Internals::ContoursFile file;
    file.frames = readFrameContours(in.contoursFile, &file.pictures);
    d.GivenContours = std::move(file);
  }
  d.Inputs = in;
  // Identified as they are when the run starts, in a thread of its own.
  const std::vector<std::pair<std::string, std::string>> files = { { "ct", in.ctPath },
    { "mesh", in.meshPath }, { "frames", in.framesPath }, { "intrinsics", in.intrinsicsPath },
    { "tracker", in.trackerPath }, { "tracker_to_ct", in.trackerToCTPath },
    { "start_poses", in.startPosesPath }, { "colmap", in.colmapFolder }, { "sfm", in.sfmFile },
    { "contours", in.contoursFile } };
  d.InputIdentities = std::async(std::launch::async,
    [files]
    {
      Internals::Identities identities;
      identities.inputs = identifyInputs(files, identities.problems);
      return identities;
    }).share();
}

void VideoRegistrationPipeline::process()
{
  Internals& d = *this->Impl;
  d.need(d.Inputs.has_value(), "prepare the inputs");
  const VideoRegistrationInputs& in = *d.Inputs;
  const std::optional<TrackerTrajectory>& tracker = d.Tracker;
  const std::vector<FramePose>& startPoses = d.StartPoses;
  this->loadFrames(
    in.framesPath, readIntrinsics(in.intrinsicsPath), in.maxFrames, in.intrinsicsPath);
  if (tracker)
  {
    // Warned about once, with the scale.
    checkTrackerOverlap(*tracker,
      vimlop::frameTimesS(d.Ids, d.TimestampsS, d.RecordedFramesPerSecond, in.framesPerSecond,
        in.timeOffsetS, nullptr));
  }
  this->loadModel(in.meshPath, in.meshPath.empty() ? in.ctPath : std::string());
  if (d.GivenContours)
  {
    this->useContours(d.GivenContours->frames, d.GivenContours->pictures, in.contoursFile);
  }
  else
  {
    this->detectContours();
  }
  if (d.GivenSfm)
  {
    this->useReconstruction(*d.GivenSfm, in.sfmFile);
  }
  else if (in.runColmap)
  {
    this->reconstructWithColmap(in.colmapExecutable);
  }
  else
  {
    this->reconstruct(in.colmapFolder);
  }
  this->estimateInitialScale(
    tracker ? &*tracker : nullptr, in.framesPerSecond, in.timeOffsetS, in.initialScale);
  this->makeData();
  if (in.startMode == StartMode::Manual)
  {
    try
    {
      this->makeManualStart(startPoses.front());
    }
    catch (const Error& e)
    {
      throwFileError(in.startPosesPath, std::string(e.what()));
    }
  }
  else if (startPoses.empty())
  {
    this->makeCanonicalStarts();
  }
  else
  {
    std::vector<CameraPose> poses;
    for (const FramePose& p : startPoses)
    {
      poses.push_back(p.cameraToWorld);
    }
    this->makeCanonicalStarts(&poses, in.startPosesPath);
  }
  this->run();
}

} // namespace vimlop
