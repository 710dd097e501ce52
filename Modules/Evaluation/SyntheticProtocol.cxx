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

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>

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
  o.contourMatch.positionCovariancePx2 = options.contourVariancePx2 * Eigen::Matrix2d::Identity();
  o.contourMatch.kappa = options.kappa;
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
      formatText("P1 %-12s TRE median %.3f mm (mean %.3f, p95 %.3f), success %.0f %%, "
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
  nlohmann::json methodsJson = nlohmann::json::object();
  for (const SyntheticProtocolMethodReport& m : this->methods)
  {
    methodsJson[m.method] = {
      { "tre_mm", { { "mean", m.treMeanMm }, { "median", m.treMedianMm }, { "p95", m.treP95Mm } } },
      { "success_rate", m.successRate },
      { "camera_position_mm", { { "median", m.cameraPositionMedianMm } } },
      { "camera_angle_deg", { { "median", m.cameraAngleMedianDeg } } },
      { "runtime_s", { { "median", m.runtimeMedianS }, { "p95", m.runtimeP95S } } }
    };
  }
  report["methods"] = methodsJson;
  return report;
}

const char* syntheticProtocolMethodNames()
{
  return "vimlop, imlp, trimmed-icp, open3d-icp, open3d-gicp";
}

void checkSyntheticProtocolMethods(const std::vector<std::string>& methods)
{
  for (auto method = methods.begin(); method != methods.end(); ++method)
  {
    const bool known = *method == "vimlop" || *method == "imlp" || *method == "trimmed-icp" ||
      *method == "open3d-icp" || *method == "open3d-gicp";
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

SyntheticProtocolReport runSyntheticProtocol(const TriangleMesh& mesh,
  const SyntheticProtocolOptions& options, const EvaluationProgress& progress)
{
  if (options.trials < 1)
  {
    throw Error("the number of trials must be at least 1");
  }
  checkSyntheticProtocolMethods(options.methods);
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
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
    const SyntheticTrial trial = makeSyntheticTrial(model, options.synthetic, trialSeed);
    for (size_t m = 0; m < options.methods.size(); ++m)
    {
      const std::string& method = options.methods[m];
      const auto start = std::chrono::steady_clock::now();
      SimilarityTransform estimate;
      std::function<void()> save;
      if (method == "open3d-icp")
      {
        estimate = peers->icpWithScale(trial.data.points, trial.initialSfmToCT);
      }
      else if (method == "open3d-gicp")
      {
        estimate = peers->generalizedIcp(trial.data.points, trial.initialSfmToCT);
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
    method.runtimeMedianS = runtime.median;
    method.runtimeP95S = runtime.p95;
    report.methods.push_back(method);
  }
  return report;
}

} // namespace vimlop
