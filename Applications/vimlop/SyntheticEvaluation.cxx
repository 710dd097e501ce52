#include "SyntheticEvaluation.h"

#include "EmbreeRegistrationModel.h"
#include "Error.h"
#include "Open3DPeers.h"
#include "Registration.h"
#include "RegistrationMetrics.h"
#include "Statistics.h"
#include "TerminalProgress.h"
#include "TrialSaving.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <ostream>

namespace vimlop
{

namespace
{

struct MethodRecord
{
  std::vector<double> tre;
  std::vector<double> cameraPosition;
  std::vector<double> cameraAngle;
  std::vector<double> runtime;
  int successes = 0;
};

nlohmann::json summaryJson(const std::vector<double>& values, bool withP95 = true)
{
  const Summary s = summarize(values);
  nlohmann::json j = { { "mean", s.mean }, { "median", s.median } };
  if (withP95)
  {
    j["p95"] = s.p95;
  }
  return j;
}

} // namespace

const char* syntheticMethodNames()
{
  return "vimlop, imlp, trimmed-icp, open3d-icp, open3d-gicp";
}

void checkSyntheticMethods(const std::vector<std::string>& methods)
{
  for (const std::string& method : methods)
  {
    const bool known = method == "vimlop" || method == "imlp" || method == "trimmed-icp" ||
      method == "open3d-icp" || method == "open3d-gicp";
    if (!known)
    {
      throw Error("unknown method '" + method + "' (expected " + syntheticMethodNames() + ")");
    }
    if (method.rfind("open3d", 0) == 0 && !Open3DPeers::available())
    {
      throw Error("method '" + method + "' needs Open3D, which this build of VIMLOP lacks");
    }
  }
}

nlohmann::json runSyntheticEvaluation(
  const TriangleMesh& mesh, const SyntheticEvaluationOptions& options, std::ostream* progress)
{
  if (options.trials < 1)
  {
    throw Error("the number of trials must be at least 1");
  }
  checkSyntheticMethods(options.methods);
  const bool wantOpen3D = std::any_of(options.methods.begin(), options.methods.end(),
    [](const std::string& m) { return m.rfind("open3d", 0) == 0; });
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  std::unique_ptr<Open3DPeers> peers;
  if (wantOpen3D)
  {
    peers = std::make_unique<Open3DPeers>(mesh);
  }

  // The method whose registration of trial 0 is saved: the first of ours.
  std::string savedMethod;
  for (const std::string& method : options.methods)
  {
    if (savedMethod.empty() && method.rfind("open3d", 0) != 0)
    {
      savedMethod = method;
    }
  }
  if (!options.saveTrialFolder.empty() && savedMethod.empty())
  {
    throw Error("--save-trial needs one of the methods vimlop, imlp, trimmed-icp");
  }

  std::map<std::string, MethodRecord> records;
  for (int trialIndex = 0; trialIndex < options.trials; ++trialIndex)
  {
    const std::uint64_t trialSeed =
      options.seed * 1000003ull + static_cast<std::uint64_t>(trialIndex);
    const SyntheticTrial trial = makeSyntheticTrial(model, options.synthetic, trialSeed);
    for (const std::string& method : options.methods)
    {
      const auto start = std::chrono::steady_clock::now();
      SimilarityTransform estimate;
      std::function<void()> saved;
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
        RegistrationOptions o;
        o.method = method == "vimlop" ? RegistrationMethod::VIMLOP
          : method == "imlp"          ? RegistrationMethod::IMLP
                                      : RegistrationMethod::TrimmedICP;
        o.contourMatch.positionCovariancePx2 = 9.0 * Eigen::Matrix2d::Identity();
        o.contourMatch.kappa = 200.0;
        o.minScale = options.minScale;
        o.maxScale = options.maxScale;
        o.threads = options.threads;
        const RegistrationResult result = registerVideo(model, trial.data, trial.initialSfmToCT, o);
        estimate = result.sfmToCT;
        if (trialIndex == 0 && method == savedMethod && !options.saveTrialFolder.empty())
        {
          saved = [&, o, result]
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
      if (saved)
      {
        saved(); // outside the timed part: it renders the frames' pictures
        saved = nullptr;
      }
      MethodRecord& r = records[method];
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
    printCount(progress, "P1: trial", trialIndex + 1, options.trials);
  }

  nlohmann::json report = { { "protocol", "P1" }, { "trials", options.trials },
    { "seed", options.seed }, { "mesh_triangles", mesh.numberOfFaces() },
    { "success_threshold_mm", options.successThresholdMm } };
  nlohmann::json methods = nlohmann::json::object();
  for (const std::string& method : options.methods)
  {
    const MethodRecord& r = records[method];
    const Summary runtime = summarize(r.runtime);
    methods[method] = { { "tre_mm", summaryJson(r.tre) },
      { "success_rate", static_cast<double>(r.successes) / options.trials },
      { "camera_position_mm", { { "median", summarize(r.cameraPosition).median } } },
      { "camera_angle_deg", { { "median", summarize(r.cameraAngle).median } } },
      { "runtime_s", { { "median", runtime.median }, { "p95", runtime.p95 } } } };
  }
  report["methods"] = methods;
  return report;
}

} // namespace vimlop
