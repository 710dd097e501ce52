#include "VideoEvaluation.h"

#include "ColmapImport.h"
#include "ColmapRunner.h"
#include "ContourEvaluation.h"
#include "EmbreeRegistrationModel.h"
#include "Error.h"
#include "OccludingContours.h"
#include "Registration.h"
#include "RegistrationMetrics.h"
#include "Rotation.h"
#include "Statistics.h"
#include "StructureFromMotion.h"
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

/**
 * The true SfM-to-CT similarity from the registered cameras: the rotation is
 * the chordal mean of R_true R_sfmᵀ over the frames (the camera centres of a
 * path along a passage are nearly collinear and leave the roll about it
 * undetermined), then the least-squares scale and translation of the centres.
 */
SimilarityTransform trueSfmToCT(const SfmReconstruction& sfm, const std::vector<CameraPose>& truth)
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

Eigen::Vector3d randomDirection(std::mt19937_64& rng)
{
  std::normal_distribution<double> normal;
  Eigen::Vector3d v;
  do
  {
    v = Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  } while (v.norm() < 1e-9);
  return v.normalized();
}

/// Camera errors of the registered frames moved to CT by `sfmToCT`.
nlohmann::json cameraErrors(const SimilarityTransform& sfmToCT, const RegistrationData& data,
  const std::vector<int>& frameOf, const std::vector<CameraPose>& truth, double trueScale,
  double seconds)
{
  std::vector<double> position;
  std::vector<double> angle;
  for (size_t j = 0; j < data.frames.size(); ++j)
  {
    const CameraPose estimate = sfmToCT.apply(data.frames[j].cameraToSfm);
    position.push_back(cameraPositionError(estimate, truth[frameOf[j]]));
    angle.push_back(cameraAngleErrorDeg(estimate, truth[frameOf[j]]));
  }
  const Summary p = summarize(position);
  const Summary a = summarize(angle);
  return { { "camera_position_mm", { { "mean", p.mean }, { "max", p.max } } },
    { "camera_angle_deg", { { "mean", a.mean }, { "max", a.max } } },
    { "scale_error_rel", std::abs(sfmToCT.scale / trueScale - 1.0) }, { "runtime_s", seconds } };
}

} // namespace

nlohmann::json runVideoEvaluation(
  const TriangleMesh& mesh, const VideoEvaluationOptions& o, std::ostream* progress)
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
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  const SimulatedVideo video = simulateVideo(model, o.simulation, progress);
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
  say("contours: precision " + std::to_string(evaluation.precision()) + ", recall " +
    std::to_string(evaluation.recall()) + ", median normal error " +
    std::to_string(evaluation.medianNormalErrorDeg()) + " deg");

  // Structure from motion.
  SfmReconstruction sfm;
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
  const SimilarityTransform truth = trueSfmToCT(sfm, video.camerasCT);
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
  const double s0 = trackerScale.scale;
  say("scale: tracker " + std::to_string(s0) + ", truth " + std::to_string(truth.scale));

  // Registration data: the registered frames with their contours.
  RegistrationData data;
  std::vector<int> frameOf;
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
    data.frames.push_back(frame);
    frameOf.push_back(static_cast<int>(f));
  }
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const SfmReconstruction::Point& p : sfm.points)
  {
    data.points.push_back(p.position);
    // SfM units² to mm² with the initial scale; the registration keeps it fixed.
    data.pointCovariances.push_back(s0 * s0 * p.covariance +
      o.pointNoiseFloorMm * o.pointNoiseFloorMm * Eigen::Matrix3d::Identity());
    centroid += truth.apply(p.position);
  }
  centroid /= static_cast<double>(sfm.points.size());

  // What SfM alone allows: its cameras moved by the true similarity.
  const nlohmann::json floor =
    cameraErrors(truth, data, frameOf, video.camerasCT, truth.scale, 0.0);
  say("SfM cameras through the true similarity: " +
    std::to_string(floor["camera_position_mm"]["mean"].get<double>()) + " mm, " +
    std::to_string(floor["camera_angle_deg"]["mean"].get<double>()) + " deg (the floor)");

  // The start: the truth with the tracker's scale, rotated about the
  // points' centroid and shifted; drawn again until every camera starts
  // inside the airway, which V-IMLOP's anatomical constraint requires.
  std::mt19937_64 rng(o.simulation.seed * 2654435761ull + 99ull);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  SimilarityTransform initial;
  bool inside = false;
  for (int draw = 0; draw < 500 && !inside; ++draw)
  {
    const Eigen::Matrix3d rotation =
      rotationFromVector((o.perturbMinDeg + unit(rng) * (o.perturbMaxDeg - o.perturbMinDeg)) *
        Degree * randomDirection(rng));
    const Eigen::Vector3d shift =
      (o.perturbMinMm + unit(rng) * (o.perturbMaxMm - o.perturbMinMm)) * randomDirection(rng);
    SimilarityTransform scaled = truth;
    // Keep the centroid of the points where the truth puts it, at the new scale.
    scaled.scale = s0;
    scaled.translation = centroid - s0 * truth.rotation * (truth.inverse().apply(centroid));
    initial.scale = s0;
    initial.rotation = rotation * scaled.rotation;
    initial.translation = rotation * (scaled.translation - centroid) + centroid + shift;
    inside = true;
    for (const VideoFrame& frame : data.frames)
    {
      inside = inside && model.isInside(initial.apply(frame.cameraToSfm.centre));
    }
  }
  if (!inside)
  {
    throw Error("P2: no perturbed start keeps every camera inside the airway");
  }

  nlohmann::json methods = nlohmann::json::object();
  for (const RegistrationMethod method : { RegistrationMethod::VIMLOP, RegistrationMethod::IMLP })
  {
    RegistrationOptions options;
    options.method = method;
    options.contourMatch.positionCovariancePx2 = o.contourVariancePx2 * Eigen::Matrix2d::Identity();
    options.contourMatch.kappa = o.kappa;
    options.minScale = s0 / o.scaleBoundFactor;
    options.maxScale = s0 * o.scaleBoundFactor;
    options.threads = o.threads;
    options.stallRelativeDecrease = o.stallRelativeDecrease;
    options.stallIterations = o.stallIterations;
    options.maxIterations = o.maxIterations;
    const auto start = std::chrono::steady_clock::now();
    const RegistrationResult result = registerVideo(model, data, initial, options);
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    methods[toString(method)] =
      cameraErrors(result.sfmToCT, data, frameOf, video.camerasCT, truth.scale, seconds);
    say(std::string(toString(method)) + ": " + methods[toString(method)].dump() + " (" +
      toString(result.termination) + " after " + std::to_string(result.iterations) +
      " iterations)");
  }

  return { { "protocol", "P2" }, { "frames", o.simulation.frames }, { "seed", o.simulation.seed },
    { "sfm", o.sfm }, { "sfm_points", sfm.points.size() },
    { "contours",
      { { "precision", evaluation.precision() }, { "recall", evaluation.recall() },
        { "normal_error_deg_median", evaluation.medianNormalErrorDeg() } } },
    { "methods", methods } };
}

} // namespace vimlop
