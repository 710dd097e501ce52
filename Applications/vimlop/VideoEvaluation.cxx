#include "VideoEvaluation.h"

#include "CanonicalPoses.h"
#include "ColmapImport.h"
#include "ColmapRunner.h"
#include "ContourEvaluation.h"
#include "EmbreeRegistrationModel.h"
#include "Error.h"
#include "MultiStartRegistration.h"
#include "OccludingContours.h"
#include "RandomDirection.h"
#include "Registration.h"
#include "RegistrationMetrics.h"
#include "Rotation.h"
#include "Statistics.h"
#include "StructureFromMotion.h"
#include "TerminalProgress.h"
#include "TrackerScale.h"

#include <Eigen/Dense>

#include <opencv2/imgcodecs.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <ostream>
#include <random>

namespace vimlop
{

namespace
{

constexpr double Degree = M_PI / 180.0;

} // namespace

/**
 * The true SfM-to-CT similarity from the registered cameras: the rotation is
 * the chordal mean of R_true R_sfmᵀ over the frames (the camera centres of a
 * path along a passage are nearly collinear and leave the roll about it
 * undetermined), then the least-squares scale and translation of the centres.
 */
SimilarityTransform similarityFromCameras(
  const SfmReconstruction& sfm, const std::vector<CameraPose>& truth)
{
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  Eigen::Vector3d meanSfm = Eigen::Vector3d::Zero();
  Eigen::Vector3d meanCT = Eigen::Vector3d::Zero();
  int n = 0;
  for (size_t f = 0; f < sfm.frames.size(); ++f)
  {
    if (sfm.frames[f].registered)
    {
      sum += truth[f].rotation * sfm.frames[f].cameraToSfm.rotation.transpose();
      meanSfm += sfm.frames[f].cameraToSfm.centre;
      meanCT += truth[f].centre;
      ++n;
    }
  }
  meanSfm /= n;
  meanCT /= n;
  SimilarityTransform t;
  t.rotation = nearestRotation(sum);
  double numerator = 0.0;
  double denominator = 0.0;
  for (size_t f = 0; f < sfm.frames.size(); ++f)
  {
    if (sfm.frames[f].registered)
    {
      const Eigen::Vector3d a = t.rotation * (sfm.frames[f].cameraToSfm.centre - meanSfm);
      numerator += (truth[f].centre - meanCT).dot(a);
      denominator += a.squaredNorm();
    }
  }
  t.scale = numerator / denominator;
  t.translation = meanCT - t.scale * t.rotation * meanSfm;
  return t;
}

VideoCase prepareVideoCase(
  const RegistrationModel& model, const VideoEvaluationOptions& o, std::ostream* progress)
{
  if (o.sfm != "builtin" && o.sfm != "colmap")
  {
    throw Error("--sfm: expected 'builtin' or 'colmap', got '" + o.sfm + "'");
  }
  if (!(o.scaleBoundFactor > 1.0))
  {
    throw Error("the scale bound factor must be greater than 1");
  }
  auto say = [&](const std::string& text)
  {
    if (progress)
    {
      *progress << "P2: " << text << "\n";
    }
  };
  const TriangleMesh& mesh = model.mesh();
  VideoCase c;
  c.video = simulateEndoscopeVideo(model, o.simulation,
    [progress](const std::string& what, int done, int total)
    {
      printCount(progress, what, done, total);
      return true;
    });
  const SimulatedVideo& video = c.video;
  const PinholeCamera& k = video.intrinsics;

  // Contours: detected on the pictures, scored against the true ones.
  OccludingContourDetector::Options denseOptions = o.contours;
  denseOptions.spacingPx = 0.0;
  const OccludingContourDetector detector(denseOptions);
  ContourEvaluation evaluation;
  std::vector<std::vector<ContourPoint>> contours;
  for (size_t f = 0; f < video.frames.size(); ++f)
  {
    const std::vector<ContourPoint> dense = detector.detect(video.frames[f]);
    const std::vector<ModelContourPoint> samples =
      extractOccludingContours(mesh, k, video.camerasCT[f]);
    std::vector<Eigen::Vector3d> points;
    for (const ModelContourPoint& s : samples)
    {
      points.push_back(s.point);
    }
    std::vector<char> visible;
    model.visibility().classify(k, video.camerasCT[f], points, visible);
    std::vector<ModelContourPoint> truth;
    std::vector<double> depths;
    for (size_t i = 0; i < samples.size(); ++i)
    {
      if (visible[i])
      {
        truth.push_back(samples[i]);
        depths.push_back(video.camerasCT[f].worldToCamera(samples[i].point).z());
      }
    }
    evaluation.addFrame(dense, truth, depths, video.depth[f]);
    contours.push_back(OccludingContourDetector::thin(dense, o.contours.spacingPx));
  }
  c.contourScores = { { "precision", evaluation.precision() }, { "recall", evaluation.recall() },
    { "normal_error_deg_median", evaluation.medianNormalErrorDeg() } };
  say("contours: precision " + std::to_string(evaluation.precision()) + ", recall " +
    std::to_string(evaluation.recall()) + ", median normal error " +
    std::to_string(evaluation.medianNormalErrorDeg()) + " deg");

  // Structure from motion.
  SfmReconstruction& sfm = c.sfm;
  if (o.sfm == "builtin")
  {
    sfm = StructureFromMotion().reconstruct(video.frames, k, video.names, progress);
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
    ColmapRunner::Options colmapOptions;
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

  // Ground truth and the initial scale from the tracker (V14).
  c.truth = similarityFromCameras(sfm, video.camerasCT);
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
  say("scale: tracker " + std::to_string(c.initialScale) + ", truth " +
    std::to_string(c.truth.scale));

  // Registration data: the registered frames with their contours.
  for (size_t f = 0; f < sfm.frames.size(); ++f)
  {
    if (!sfm.frames[f].registered)
    {
      continue;
    }
    VideoFrame frame;
    frame.frameId = static_cast<int>(f);
    frame.intrinsics = sfm.frames[f].intrinsics;
    frame.intrinsics.distortion.resize(0);
    frame.cameraToSfm = sfm.frames[f].cameraToSfm;
    frame.contour = contours[f];
    c.data.frames.push_back(frame);
    c.frameOf.push_back(static_cast<int>(f));
  }
  const double s0 = c.initialScale;
  c.centroidCT = Eigen::Vector3d::Zero();
  for (const SfmReconstruction::Point& p : sfm.points)
  {
    c.data.points.push_back(p.position);
    // SfM units² to mm² with the initial scale; the registration keeps it fixed.
    c.data.pointCovariances.push_back(s0 * s0 * p.covariance +
      o.pointNoiseFloorMm * o.pointNoiseFloorMm * Eigen::Matrix3d::Identity());
    c.centroidCT += c.truth.apply(p.position);
  }
  c.centroidCT /= static_cast<double>(sfm.points.size());

  // What SfM alone allows: its cameras moved by the true similarity.
  c.floor = cameraErrors(c, c.truth, 0.0);
  say("SfM cameras through the true similarity: " +
    std::to_string(c.floor["camera_position_mm"]["mean"].get<double>()) + " mm, " +
    std::to_string(c.floor["camera_angle_deg"]["mean"].get<double>()) + " deg (the floor)");
  return c;
}

nlohmann::json cameraErrors(const VideoCase& c, const SimilarityTransform& sfmToCT, double seconds)
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
  return { { "camera_position_mm", { { "mean", p.mean }, { "max", p.max } } },
    { "camera_angle_deg", { { "mean", a.mean }, { "max", a.max } } },
    { "scale_error_rel", std::abs(sfmToCT.scale / c.truth.scale - 1.0) },
    { "runtime_s", seconds } };
}

std::vector<double> cameraPositionErrorsMm(const VideoCase& c, const SimilarityTransform& sfmToCT)
{
  std::vector<double> position;
  for (size_t j = 0; j < c.data.frames.size(); ++j)
  {
    const CameraPose estimate = sfmToCT.apply(c.data.frames[j].cameraToSfm);
    position.push_back(cameraPositionError(estimate, c.video.camerasCT[c.frameOf[j]]));
  }
  return position;
}

SimilarityTransform perturbedStart(const VideoCase& c, const RegistrationModel& model,
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
    bool inside = true;
    for (const VideoFrame& frame : c.data.frames)
    {
      inside = inside && model.isInside(initial.apply(frame.cameraToSfm.centre));
    }
    if (inside)
    {
      return initial;
    }
  }
  throw Error("P2: no perturbed start keeps every camera inside the airway");
}

RegistrationOptions videoRegistrationOptions(
  double initialScale, const VideoEvaluationOptions& o, RegistrationMethod method)
{
  RegistrationOptions options;
  options.method = method;
  options.contourMatch.positionCovariancePx2 = o.contourVariancePx2 * Eigen::Matrix2d::Identity();
  options.contourMatch.kappa = o.kappa;
  options.minScale = initialScale / o.scaleBoundFactor;
  options.maxScale = initialScale * o.scaleBoundFactor;
  options.threads = o.threads;
  options.stallRelativeDecrease = o.stallRelativeDecrease;
  options.stallIterations = o.stallIterations;
  options.maxIterations = o.maxIterations;
  return options;
}

std::vector<SimilarityTransform> canonicalStarts(const RegistrationData& data, double initialScale,
  const std::vector<CameraPose>& posesCT, int* anchorFrame)
{
  // The middle registered frame stands at each canonical pose: the sequence
  // then reaches both ways from it, as the scope moves through the region.
  if (data.frames.empty())
  {
    throw Error("canonical starts: no registered frame");
  }
  const size_t anchor = data.frames.size() / 2;
  if (anchorFrame)
  {
    *anchorFrame = data.frames[anchor].frameId;
  }
  std::vector<SimilarityTransform> starts;
  for (const CameraPose& pose : posesCT)
  {
    starts.push_back(startFromCameraPose(pose, data.frames[anchor].cameraToSfm, initialScale));
  }
  return starts;
}

nlohmann::json runVideoEvaluation(
  const TriangleMesh& mesh, const VideoEvaluationOptions& o, std::ostream* progress)
{
  if (o.init != "perturbed" && o.init != "canonical")
  {
    throw Error("--init: expected 'perturbed' or 'canonical', got '" + o.init + "'");
  }
  auto say = [&](const std::string& text)
  {
    if (progress)
    {
      *progress << "P2: " << text << "\n";
    }
  };
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  VideoEvaluationOptions simulated = o;
  if (o.init == "canonical" && simulated.simulation.trajectory.uprightRollDeg < 0.0)
  {
    // Canonical poses assume the scope is held upright (see CanonicalPoses.h).
    simulated.simulation.trajectory.uprightRollDeg = o.uprightRollDeg;
  }
  const VideoCase c = prepareVideoCase(model, simulated, progress);

  nlohmann::json result = { { "protocol", "P2" }, { "frames", o.simulation.frames },
    { "seed", o.simulation.seed }, { "sfm", o.sfm }, { "sfm_points", c.sfm.points.size() },
    { "contours", c.contourScores }, { "sfm_floor", c.floor }, { "init", o.init } };

  std::vector<SimilarityTransform> starts;
  if (o.init == "perturbed")
  {
    std::mt19937_64 rng(o.simulation.seed * 2654435761ull + 99ull);
    starts.push_back(perturbedStart(
      c, model, rng, o.perturbMinMm, o.perturbMaxMm, o.perturbMinDeg, o.perturbMaxDeg));
  }
  else
  {
    const std::vector<CameraPose> poses = makeCanonicalPoses(model, o.canonical);
    int anchor = 0;
    starts = canonicalStarts(c.data, c.initialScale, poses, &anchor);
    say("canonical poses: " + std::to_string(poses.size()) + " (frame " + std::to_string(anchor) +
      " placed at each), " + std::to_string(poses.size() * o.multiStart.scaleFactors.size()) +
      " candidates");
    result["candidates"] = poses.size() * o.multiStart.scaleFactors.size();
  }

  nlohmann::json methods = nlohmann::json::object();
  for (const RegistrationMethod method : { RegistrationMethod::VIMLOP, RegistrationMethod::IMLP })
  {
    const RegistrationOptions options = videoRegistrationOptions(c.initialScale, o, method);
    const auto start = std::chrono::steady_clock::now();
    RegistrationResult r;
    nlohmann::json extra = nlohmann::json::object();
    if (o.init == "perturbed")
    {
      r = registerVideo(model, c.data, starts.front(), options);
    }
    else
    {
      MultiStartOptions m = o.multiStart;
      m.registration = options;
      m.threads = o.threads;
      const MultiStartResult ms = registerMultiStart(model, c.data, starts, m,
        [&](const char* phase, int done, int total)
        {
          if (progress && (done == total || done % 20 == 0))
          {
            *progress << "P2: " << toString(method) << " multi-start " << phase << " " << done
                      << "/" << total << "\n";
          }
          return true;
        });
      r = ms.best;
      int skipped = 0;
      for (const MultiStartCandidate& candidate : ms.candidates)
      {
        skipped += !candidate.skipped.empty();
      }
      extra = { { "failure_flag", ms.failure }, { "contour_error_px", ms.best.contourErrorPx },
        { "matched_fraction", matchedContourFraction(ms.best) },
        { "failure_threshold_px", ms.failureThresholdPx }, { "winner", ms.bestCandidate },
        { "skipped_candidates", skipped } };
    }
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json errors = cameraErrors(c, r.sfmToCT, seconds);
    errors.update(extra);
    methods[toString(method)] = errors;
    say(std::string(toString(method)) + ": " + errors.dump() + " (" + toString(r.termination) +
      " after " + std::to_string(r.iterations) + " iterations)");
  }
  result["methods"] = methods;
  return result;
}

} // namespace vimlop
