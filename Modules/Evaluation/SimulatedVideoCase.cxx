#include <vimlop/Evaluation/SimulatedVideoCase.h>

#include <vimlop/Core/AnatomicalConstraint.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/RandomDirection.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Evaluation/ProgressNoteStream.h>
#include <vimlop/Pipeline/SimilarityFromCameras.h>
#include <vimlop/Pipeline/VideoRegistrationData.h>
#include <vimlop/Video/ColmapImport.h>
#include <vimlop/Video/ColmapRunner.h>
#include <vimlop/Video/StructureFromMotion.h>
#include <vimlop/Video/TrackerScale.h>

#include <opencv2/imgcodecs.hpp>

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
  const RegistrationModel& model, const VideoProtocolOptions& o, const EvaluationProgress& progress)
{
  auto say = [&](const std::string& text) { reportEvaluationNote(progress, "P2: " + text); };
  SimulatedVideoCase c;
  c.video = simulateEndoscopeVideo(model, o.simulation, progress);
  const SimulatedVideo& video = c.video;
  const PinholeCamera& k = video.intrinsics;

  // Contours: detected on the pictures, scored against the true ones.
  ScoredContours scored = detectAndScoreContours(model, video, o.pipeline.contours);
  const std::vector<std::vector<ContourPoint>>& contours = scored.contoursPerFrame;
  c.contourScores = scored.scores;
  say("contours: precision " + std::to_string(c.contourScores.precision) + ", recall " +
    std::to_string(c.contourScores.recall) + ", median normal error " +
    std::to_string(c.contourScores.normalErrorDegMedian) + " deg");

  // Structure from motion.
  SfmReconstruction& sfm = c.sfm;
  if (o.sfm == "builtin")
  {
    ProgressNoteStream log(progress);
    sfm = StructureFromMotion().reconstruct(video.frames, k, video.names, log.stream());
    log.throwIfCancelled();
  }
  else
  {
    namespace fs = std::filesystem;
    const std::string work = o.workFolder.empty() ? "p2-colmap" : o.workFolder;
    const std::string images = (fs::path(work) / "images").string();
    std::error_code ec;
    fs::remove_all(images, ec);
    fs::create_directories(images, ec);
    for (size_t f = 0; f < video.frames.size(); ++f)
    {
      cv::imwrite((fs::path(images) / video.names[f]).string(), video.frames[f]);
    }
    ColmapRunnerOptions colmapOptions;
    colmapOptions.executable = o.colmapExecutable;
    const std::string modelFolder =
      ColmapRunner(colmapOptions).run(images, k, (fs::path(work) / "colmap").string());
    std::vector<std::string> warnings;
    sfm = readColmapModel(modelFolder, ColmapFormat::Binary, video.names, 0.5, &warnings);
    for (const std::string& w : warnings)
    {
      say(w);
    }
  }
  if (sfm.numberOfRegisteredFrames() < 2 || sfm.points.size() < 10)
  {
    throw Error("P2: SfM registered " + std::to_string(sfm.numberOfRegisteredFrames()) +
      " frames and " + std::to_string(sfm.points.size()) + " points; too few to register");
  }
  say("SfM (" + o.sfm + "): " + std::to_string(sfm.numberOfRegisteredFrames()) + "/" +
    std::to_string(sfm.frames.size()) + " frames, " + std::to_string(sfm.points.size()) +
    " points, RMS reprojection error " + std::to_string(sfm.rmsReprojectionErrorPx()) + " px");

  // The initial scale from the tracker (V14).
  std::vector<Eigen::Vector3d> centres;
  for (const SfmReconstruction::Frame& f : sfm.frames)
  {
    centres.push_back(f.registered
        ? f.cameraToSfm.centre
        : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  }
  const TrackerScaleResult trackerScale =
    estimateTrackerScale(video.tracker, video.frameTimesS, centres);
  for (const std::string& w : trackerScale.warnings)
  {
    say(w);
  }
  c.initialScale = trackerScale.scale;

  // Registration data: the registered frames with their contours.
  c.data = makeVideoRegistrationData(
    sfm, contours, c.initialScale, o.pipeline.pointNoiseFloorMm, &c.frameOf);
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
