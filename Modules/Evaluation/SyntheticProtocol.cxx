#include <vimlop/Evaluation/SyntheticProtocol.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Registration.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/Peers/Open3DPeers.h>
#include <vimlop/Evaluation/TrialSaving.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Results/RegistrationRecordIO.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>

namespace vimlop
{

namespace
{

/// Every trial's errors of one method, summarised at the end.
struct MethodRecord
{
  std::vector<double> tre;
  std::vector<double> cameraPosition;
  std::vector<double> cameraAngle;
  std::vector<double> runtime;
  std::vector<double> residual;
  int successes = 0;
};

bool isOpen3D(const std::string& method)
{
  return method.rfind("open3d", 0) == 0;
}

RegistrationOptions registrationOptions(
  const std::string& method, const SyntheticProtocolOptions& options)
{
  RegistrationOptions o;
  o.method = registrationMethodFromString(method);
  // The assumed noise model: scaled variances, and the orientation's
  // variance 1/κ scaled alike.
  o.contourMatch.positionCovariancePx2 =
    options.assumedNoiseScale * options.contourVariancePx2 * Eigen::Matrix2d::Identity();
  o.contourMatch.kappa = options.kappa / options.assumedNoiseScale;
  o.robustContourInflation = options.robustContourInflation;
  o.stallRelativeDecrease = options.stallRelativeDecrease;
  o.stallIterations = options.stallIterations;
  o.maxIterations = options.maxIterations;
  o.minScale = options.minScale;
  o.maxScale = options.maxScale;
  o.threads = options.threads;
  return o;
}

} // namespace

std::vector<std::string> SyntheticProtocolReport::summaryLines() const
{
  std::vector<std::string> lines;
  for (const SyntheticProtocolMethodReport& m : this->methods)
  {
    lines.push_back(
      formatText("P1 %-20s TRE median %.3f mm (mean %.3f, p95 %.3f), success %.0f %%, "
                 "camera %.3f mm / %.3f deg, runtime median %.3f s",
        m.method.c_str(), m.treMedianMm, m.treMeanMm, m.treP95Mm, 100.0 * m.successRate,
        m.cameraPositionMedianMm, m.cameraAngleMedianDeg, m.runtimeMedianS));
  }
  return lines;
}

nlohmann::json SyntheticProtocolReport::toJson() const
{
  nlohmann::json report = { { "protocol", "P1" }, { "trials", this->trials },
    { "seed", this->seed }, { "mesh_triangles", this->meshTriangles },
    { "success_threshold_mm", this->successThresholdMm } };
  nlohmann::json modelError = this->dataSurface.toJson();
  modelError["data_surface_triangles"] = this->dataSurfaceTriangles;
  modelError["assumed_noise_scale"] = this->assumedNoiseScale;
  modelError["start_scale_error"] = this->startScaleError;
  report["model_error"] = modelError;
  report["robust_contour_inflation"] = this->robustContourInflation;
  nlohmann::json methodsJson = nlohmann::json::object();
  for (const SyntheticProtocolMethodReport& m : this->methods)
  {
    methodsJson[m.method] = {
      { "tre_mm", { { "mean", m.treMeanMm }, { "median", m.treMedianMm }, { "p95", m.treP95Mm } } },
      { "success_rate", m.successRate },
      { "camera_position_mm", { { "median", m.cameraPositionMedianMm } } },
      { "camera_angle_deg", { { "median", m.cameraAngleMedianDeg } } },
      { "residual_mm", { { "median", m.residualMedianMm } } },
      { "runtime_s", { { "median", m.runtimeMedianS }, { "p95", m.runtimeP95S } } }
    };
  }
  report["methods"] = methodsJson;
  return report;
}

const char* syntheticProtocolMethodNames()
{
  return "vimlop, imlp, trimmed-icp, open3d-icp, open3d-gicp, open3d-icp-prebuilt, "
         "open3d-gicp-prebuilt";
}

void checkSyntheticProtocolMethods(const std::vector<std::string>& methods)
{
  for (auto method = methods.begin(); method != methods.end(); ++method)
  {
    const bool known = *method == "vimlop" || *method == "imlp" || *method == "trimmed-icp" ||
      *method == "open3d-icp" || *method == "open3d-gicp" || *method == "open3d-icp-prebuilt" ||
      *method == "open3d-gicp-prebuilt";
    if (!known)
    {
      throw Error(
        "unknown method '" + *method + "' (expected " + syntheticProtocolMethodNames() + ")");
    }
    if (isOpen3D(*method) && !Open3DPeers::available())
    {
      throw Error("method '" + *method + "' needs Open3D, which this build of VIMLOP lacks");
    }
    if (std::find(methods.begin(), method, *method) != method)
    {
      throw Error("method '" + *method + "' is listed twice");
    }
  }
}

void validateSyntheticProtocolOptions(const SyntheticProtocolOptions& options)
{
  if (options.trials < 1)
  {
    throw Error("the number of trials must be at least 1");
  }
  if (!(options.assumedNoiseScale > 0.0 && std::isfinite(options.assumedNoiseScale)))
  {
    throw Error(formatText("P1: the assumed noise scale must be a finite number > 0, not %g",
      options.assumedNoiseScale));
  }
  const double startScale = 1.0 + options.synthetic.startScaleError;
  if (!(startScale >= options.minScale && startScale <= options.maxScale))
  {
    throw Error(formatText("P1: the start's scale 1 + %g lies outside the scale bounds [%g, %g]",
      options.synthetic.startScaleError, options.minScale, options.maxScale));
  }
  options.dataSurfaceMaking.validate();
}

SyntheticProtocolReport runSyntheticProtocol(const TriangleMesh& mesh,
  const SyntheticProtocolOptions& options, const EvaluationProgress& progress)
{
  validateSyntheticProtocolOptions(options);
  checkSyntheticProtocolMethods(options.methods);
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  // The anatomy the data are drawn from: the model unless given.
  std::optional<RegistrationModel> dataModel;
  if (options.dataSurface.numberOfFaces() > 0)
  {
    dataModel.emplace(makeEmbreeRegistrationModel(options.dataSurface));
  }
  const RegistrationModel& dataSurface = dataModel ? *dataModel : model;
  std::unique_ptr<Open3DPeers> peers;
  if (std::any_of(options.methods.begin(), options.methods.end(), isOpen3D))
  {
    peers = std::make_unique<Open3DPeers>(mesh);
  }

  // The method whose registration of trial 0 is saved: the first of ours.
  const auto saved = std::find_if_not(options.methods.begin(), options.methods.end(), isOpen3D);
  if (!options.saveTrialFolder.empty() && saved == options.methods.end())
  {
    throw Error("--save-trial needs one of the methods vimlop, imlp, trimmed-icp");
  }

  std::vector<MethodRecord> records(options.methods.size());
  for (int trialIndex = 0; trialIndex < options.trials; ++trialIndex)
  {
    const std::uint64_t trialSeed =
      options.seed * 1000003ull + static_cast<std::uint64_t>(trialIndex);
    SyntheticTrial trial = makeSyntheticTrial(model, dataSurface, options.synthetic, trialSeed);
    for (Eigen::Matrix3d& covariance : trial.data.pointCovariances)
    {
      covariance *= options.assumedNoiseScale;
    }
    for (size_t m = 0; m < options.methods.size(); ++m)
    {
      const std::string& method = options.methods[m];
      const auto start = std::chrono::steady_clock::now();
      SimilarityTransform estimate;
      std::function<void()> save;
      const Open3DPeers::TargetTree tree =
        method.size() > 9 && method.compare(method.size() - 9, 9, "-prebuilt") == 0
        ? Open3DPeers::TargetTree::Prebuilt
        : Open3DPeers::TargetTree::PerCall;
      if (method.rfind("open3d-icp", 0) == 0)
      {
        estimate = peers->icpWithScale(trial.data.points, trial.initialSfmToCT, tree);
      }
      else if (method.rfind("open3d-gicp", 0) == 0)
      {
        estimate = peers->generalizedIcp(trial.data.points, trial.initialSfmToCT, tree);
      }
      else
      {
        const RegistrationOptions o = registrationOptions(method, options);
        const RegistrationResult result = registerVideo(model, trial.data, trial.initialSfmToCT, o);
        estimate = result.sfmToCT;
        if (trialIndex == 0 && method == *saved && !options.saveTrialFolder.empty())
        {
          save = [&, o, result]
          {
            saveSyntheticTrial(options.saveTrialFolder,
              "vimlop evaluate synthetic (P1), seed " + std::to_string(options.seed) +
                ", trial 0, " + method,
              mesh, trial, o, result);
          };
        }
      }
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (save)
      {
        save(); // outside the timed part: it renders the frames' pictures
      }
      MethodRecord& r = records[m];
      const double tre = targetRegistrationError(estimate, trial.truthSfmToCT, trial.targetsCT);
      r.tre.push_back(tre);
      r.successes += tre < options.successThresholdMm;
      r.runtime.push_back(seconds);
      double residualSum = 0.0;
      for (const Eigen::Vector3d& point : trial.data.points)
      {
        residualSum += model.locator().closestPoint(estimate.apply(point)).distanceMm;
      }
      r.residual.push_back(residualSum / static_cast<double>(trial.data.points.size()));
      for (size_t c = 0; c < trial.trueCamerasCT.size(); ++c)
      {
        const CameraPose camera = estimate.apply(trial.data.frames[c].cameraToSfm);
        r.cameraPosition.push_back(cameraPositionError(camera, trial.trueCamerasCT[c]));
        r.cameraAngle.push_back(cameraAngleErrorDeg(camera, trial.trueCamerasCT[c]));
      }
    }
    reportEvaluationCount(progress, "P1: trial", trialIndex + 1, options.trials);
  }

  SyntheticProtocolReport report;
  report.trials = options.trials;
  report.seed = options.seed;
  report.meshTriangles = mesh.numberOfFaces();
  report.successThresholdMm = options.successThresholdMm;
  report.dataSurface = options.dataSurfaceMaking;
  report.dataSurfaceTriangles = options.dataSurface.numberOfFaces();
  report.assumedNoiseScale = options.assumedNoiseScale;
  report.robustContourInflation = options.robustContourInflation;
  report.startScaleError = options.synthetic.startScaleError;
  for (size_t m = 0; m < options.methods.size(); ++m)
  {
    const MethodRecord& r = records[m];
    const Summary tre = summarize(r.tre);
    const Summary runtime = summarize(r.runtime);
    SyntheticProtocolMethodReport method;
    method.method = options.methods[m];
    method.treMeanMm = tre.mean;
    method.treMedianMm = tre.median;
    method.treP95Mm = tre.p95;
    method.successRate = static_cast<double>(r.successes) / options.trials;
    method.cameraPositionMedianMm = summarize(r.cameraPosition).median;
    method.cameraAngleMedianDeg = summarize(r.cameraAngle).median;
    method.residualMedianMm = summarize(r.residual).median;
    method.runtimeMedianS = runtime.median;
    method.runtimeP95S = runtime.p95;
    report.methods.push_back(method);
  }
  return report;
}

} // namespace vimlop
