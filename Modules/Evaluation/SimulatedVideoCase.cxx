#include <vimlop/Evaluation/SimulatedVideoCase.h>

#include <vimlop/Core/AnatomicalConstraint.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/RandomDirection.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Evaluation/LensDistortionRendering.h>
#include <vimlop/Evaluation/ProgressNoteStream.h>
#include <vimlop/Pipeline/SimilarityFromCameras.h>
#include <vimlop/Pipeline/VideoRegistrationPipeline.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Video/ColmapRunner.h>
#include <vimlop/Video/IntrinsicsIO.h>
#include <vimlop/Video/TrackerTrajectory.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

namespace vimlop
{

namespace
{

constexpr double Degree = M_PI / 180.0;

} // namespace

SimulatedVideoCase prepareSimulatedVideoCase(
  const SimulatedWorld& world, const VideoProtocolOptions& o, const EvaluationProgress& progress)
{
  namespace fs = std::filesystem;
  auto say = [&](const std::string& text) { reportEvaluationNote(progress, "P2: " + text); };
  SimulatedVideoCase c;
  const RegistrationModel truth = makeEmbreeRegistrationModel(world.truth);
  c.video = simulateEndoscopeVideo(truth, o.simulation, progress);
  const SimulatedVideo& video = c.video;

  // The sequence as a user has it, the truth apart; the main job reads it.
  const fs::path work = o.workFolder.empty() ? fs::temp_directory_path() /
      ("vimlop-sequence-" + std::to_string(::getpid()) + "-" + std::to_string(o.simulation.seed))
                                             : fs::path(o.workFolder);
  const fs::path folder = work / "sequence";
  std::error_code ec;
  fs::remove_all(folder, ec);
  writeSimulatedVideo(video, folder.string());
  fs::remove_all(folder / "truth", ec);

  auto pipeline = std::make_shared<VideoRegistrationPipeline>(o.pipeline);
  // The pipeline outlives this function (the caller registers with it): its
  // handlers hold copies, and its log, local here, is detached before returning.
  pipeline->setWarningHandler(
    [progress](const std::string& w) { reportEvaluationNote(progress, "P2: " + w); });
  ProgressNoteStream log(progress);
  pipeline->setLog(log.stream());
  pipeline->loadModel(world.model);
  pipeline->loadFrames(
    (folder / "frames").string(), readIntrinsics((folder / "intrinsics.yaml").string()));
  pipeline->detectContours();
  if (o.sfm == "builtin")
  {
    pipeline->reconstruct();
  }
  else
  {
    ColmapRunnerOptions colmapOptions;
    colmapOptions.executable = o.colmapExecutable;
    pipeline->reconstruct(
      ColmapRunner(colmapOptions)
        .run((folder / "frames").string(), pipeline->intrinsics(), (work / "colmap").string()));
  }
  const TrackerTrajectory tracker = TrackerTrajectory::readCsv((folder / "tracker.csv").string());
  pipeline->estimateInitialScale(&tracker, o.simulation.framesPerSecond, 0.0, 0.0);
  pipeline->makeData();
  log.throwIfCancelled();
  pipeline->setLog(nullptr);
  if (o.workFolder.empty())
  {
    fs::remove_all(work, ec);
  }
  c.sfm = pipeline->sfm();
  c.initialScale = pipeline->initialScale();
  c.data = pipeline->data();
  c.frameOf = pipeline->frameOf();
  c.pipeline = pipeline;
  say("SfM (" + o.sfm + "): " + std::to_string(c.sfm.numberOfRegisteredFrames()) + "/" +
    std::to_string(c.sfm.frames.size()) + " frames, " + std::to_string(c.sfm.points.size()) +
    " points, RMS reprojection error " + std::to_string(c.sfm.rmsReprojectionErrorPx()) + " px");

  // The contours, scored against the true ones: the detector on the raw
  // frames, dense and without the field stop's mask (the registration uses
  // the pipeline's, masked). Distorted frames are not scored: the true
  // contours are a pinhole camera's.
  if (video.intrinsics.hasDistortion())
  {
    c.contourScores.precision = c.contourScores.recall = c.contourScores.normalErrorDegMedian =
      std::numeric_limits<double>::quiet_NaN();
    say("contours: not scored (the frames are distorted; the true contours are a pinhole's)");
  }
  else
  {
    c.contourScores = detectAndScoreContours(truth, video, o.pipeline.contours).scores;
    say("contours: precision " + std::to_string(c.contourScores.precision) + ", recall " +
      std::to_string(c.contourScores.recall) + ", median normal error " +
      std::to_string(c.contourScores.normalErrorDegMedian) + " deg");
  }

  setCaseTruth(c);
  say("scale: tracker " + std::to_string(c.initialScale) + ", truth " +
    std::to_string(c.truth.scale));
  say("SfM cameras through the true similarity: " + std::to_string(c.floor.positionMeanMm) +
    " mm, " + std::to_string(c.floor.angleMeanDeg) + " deg (the floor)");
  return c;
}

void setCaseTruth(SimulatedVideoCase& c)
{
  c.truth = similarityFromCameras(c.sfm, c.video.camerasCT);
  c.centroidCT = Eigen::Vector3d::Zero();
  for (const SfmReconstruction::Point& p : c.sfm.points)
  {
    c.centroidCT += c.truth.apply(p.position);
  }
  c.centroidCT /= static_cast<double>(c.sfm.points.size());
  // What SfM alone allows: its cameras moved by the true similarity.
  c.floor = cameraErrors(c, c.truth, 0.0);
}

VideoCameraErrors cameraErrors(
  const SimulatedVideoCase& c, const SimilarityTransform& sfmToCT, double seconds)
{
  const std::vector<double> position = cameraPositionErrorsMm(c, sfmToCT);
  std::vector<double> angle;
  for (size_t j = 0; j < c.data.frames.size(); ++j)
  {
    const CameraPose estimate = sfmToCT.apply(c.data.frames[j].cameraToSfm);
    angle.push_back(cameraAngleErrorDeg(estimate, c.video.camerasCT[c.frameOf[j]]));
  }
  const Summary p = summarize(position);
  const Summary a = summarize(angle);
  VideoCameraErrors e;
  e.positionMeanMm = p.mean;
  e.positionMaxMm = p.max;
  e.angleMeanDeg = a.mean;
  e.angleMaxDeg = a.max;
  e.scaleErrorRel = std::abs(sfmToCT.scale / c.truth.scale - 1.0);
  e.runtimeS = seconds;
  return e;
}

std::vector<double> cameraPositionErrorsMm(
  const SimulatedVideoCase& c, const SimilarityTransform& sfmToCT)
{
  std::vector<double> position;
  for (size_t j = 0; j < c.data.frames.size(); ++j)
  {
    const CameraPose estimate = sfmToCT.apply(c.data.frames[j].cameraToSfm);
    position.push_back(cameraPositionError(estimate, c.video.camerasCT[c.frameOf[j]]));
  }
  return position;
}

SimilarityTransform perturbedStart(const SimulatedVideoCase& c, const RegistrationModel& model,
  std::mt19937_64& rng, double minMm, double maxMm, double minDeg, double maxDeg)
{
  // The truth with the tracker's scale, rotated about the points' centroid
  // and shifted; drawn again until every camera starts inside the airway,
  // which V-IMLOP's anatomical constraint requires.
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double s0 = c.initialScale;
  SimilarityTransform scaled = c.truth;
  // Keep the centroid of the points where the truth puts it, at the new scale.
  scaled.scale = s0;
  scaled.translation =
    c.centroidCT - s0 * c.truth.rotation * (c.truth.inverse().apply(c.centroidCT));
  for (int draw = 0; draw < 500; ++draw)
  {
    const Eigen::Matrix3d rotation =
      rotationFromVector((minDeg + unit(rng) * (maxDeg - minDeg)) * Degree * randomDirection(rng));
    const Eigen::Vector3d shift = (minMm + unit(rng) * (maxMm - minMm)) * randomDirection(rng);
    SimilarityTransform initial;
    initial.scale = s0;
    initial.rotation = rotation * scaled.rotation;
    initial.translation = rotation * (scaled.translation - c.centroidCT) + c.centroidCT + shift;
    if (camerasInside(model, c.data.frames, initial))
    {
      return initial;
    }
  }
  throw Error("P2: no perturbed start keeps every camera inside the airway");
}

} // namespace vimlop
