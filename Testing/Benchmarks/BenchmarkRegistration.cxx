// Speed of V-IMLOP on the P1 problem (6 frames, 900 points) and on a
// 30-frame, 2300-point problem: median registration time, time per iteration
// by stage, and the speed-up of the most-likely-point tree over brute force,
// all measured in the same run (the machines are shared; compare ratios).
//
// Usage: VIMLOPBenchmarkRegistration --mesh airway.vtp [--trials N] [--threads T] [--json out.json]

#include <vimlop/Core/Error.h>
#include <vimlop/Core/MeshTree.h>
#include <vimlop/Core/Registration.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <nlohmann/json.hpp>

#include <vtkPolyData.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

using namespace vimlop;

namespace
{

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct ProblemTimes
{
  std::vector<double> seconds;
  std::vector<double> iterations;
  StageTimes perIteration; // mean over every iteration of every trial
  std::vector<double> tre;
};

ProblemTimes run(
  const RegistrationModel& model, const SyntheticOptions& synthetic, int trials, int threads)
{
  ProblemTimes t;
  int totalIterations = 0;
  for (int i = 0; i < trials; ++i)
  {
    const SyntheticTrial trial = makeSyntheticTrial(model, synthetic, 1000 + i);
    RegistrationOptions options;
    options.minScale = 0.8;
    options.maxScale = 1.25;
    options.threads = threads;
    const auto start = Clock::now();
    const RegistrationResult result =
      registerVideo(model, trial.data, trial.initialSfmToCT, options);
    t.seconds.push_back(secondsSince(start));
    t.iterations.push_back(result.iterations);
    t.tre.push_back(targetRegistrationError(result.sfmToCT, trial.truthSfmToCT, trial.targetsCT));
    for (const IterationRecord& r : result.history)
    {
      t.perIteration.match3dMs += r.times.match3dMs;
      t.perIteration.contoursMs += r.times.contoursMs;
      t.perIteration.visibilityMs += r.times.visibilityMs;
      t.perIteration.match2dMs += r.times.match2dMs;
      t.perIteration.outliersMs += r.times.outliersMs;
      t.perIteration.updateMs += r.times.updateMs;
      t.perIteration.constraintMs += r.times.constraintMs;
      ++totalIterations;
    }
  }
  const double n = std::max(totalIterations, 1);
  StageTimes& s = t.perIteration;
  s.match3dMs /= n;
  s.contoursMs /= n;
  s.visibilityMs /= n;
  s.match2dMs /= n;
  s.outliersMs /= n;
  s.updateMs /= n;
  s.constraintMs /= n;
  return t;
}

nlohmann::json report(const char* name, const ProblemTimes& t)
{
  const StageTimes& s = t.perIteration;
  std::printf("%s: median %.3f s (p95 %.3f), %.1f iterations, TRE median %.3f mm\n", name,
    summarize(t.seconds).median, summarize(t.seconds).p95, summarize(t.iterations).median,
    summarize(t.tre).median);
  std::printf("  per iteration, ms: 3D match %.2f, contours %.2f, visibility %.2f, 2D match %.2f, "
              "outliers %.2f, update %.2f, constraint %.2f\n",
    s.match3dMs, s.contoursMs, s.visibilityMs, s.match2dMs, s.outliersMs, s.updateMs,
    s.constraintMs);
  return { { "median_s", summarize(t.seconds).median }, { "p95_s", summarize(t.seconds).p95 },
    { "iterations_median", summarize(t.iterations).median },
    { "tre_median_mm", summarize(t.tre).median },
    { "per_iteration_ms",
      { { "match3d", s.match3dMs }, { "contours", s.contoursMs }, { "visibility", s.visibilityMs },
        { "match2d", s.match2dMs }, { "outliers", s.outliersMs }, { "update", s.updateMs },
        { "constraint", s.constraintMs } } } };
}

} // namespace

int main(int argc, char** argv)
{
  std::string meshPath;
  std::string jsonPath;
  int trials = 10;
  int threads = 0;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    if (!std::strcmp(argv[i], "--mesh"))
      meshPath = argv[i + 1];
    else if (!std::strcmp(argv[i], "--trials"))
      trials = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--threads"))
      threads = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--json"))
      jsonPath = argv[i + 1];
  }
  if (meshPath.empty() || trials < 1)
  {
    std::fprintf(stderr,
      "usage: %s --mesh airway.vtp [--trials N] [--threads T] [--json out.json]\n", argv[0]);
    return 2;
  }
  try
  {
    const TriangleMesh mesh = toTriangleMesh(readPolyData(meshPath));
    const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
    std::printf("mesh: %d triangles; %d trials per problem; threads %d\n", mesh.numberOfFaces(),
      trials, threads);
    nlohmann::json out;

    SyntheticOptions p1;
    out["p1"] = report("P1 (6 frames, 900 points)", run(model, p1, trials, threads));

    SyntheticOptions video = p1;
    video.cameras = 30;
    video.points = 2300;
    video.cameraStepMm = 0.3;
    out["video30"] = report("30 frames, 2300 points", run(model, video, trials, threads));

    // Tree against brute force on the same most-likely-point queries: the
    // SfM points at their true place, with their covariances in the CT frame.
    const SyntheticTrial trial = makeSyntheticTrial(model, p1, 7);
    const int queries = 300;
    const SimilarityTransform& truth = trial.truthSfmToCT;
    const Eigen::Matrix3d toCT = truth.scale * truth.rotation;
    std::vector<Eigen::Vector3d> queryPoints(queries);
    std::vector<Eigen::Matrix3d> queryCovariances(queries);
    for (int i = 0; i < queries; ++i)
    {
      queryPoints[i] = truth.apply(trial.data.points[i]);
      queryCovariances[i] = toCT * trial.data.pointCovariances[i] * toCT.transpose();
    }
    const long long facesBefore = MeshTree::facesVisited();
    auto start = Clock::now();
    double checksum = 0.0;
    for (int i = 0; i < queries; ++i)
    {
      checksum += model.tree().mostLikelyPoint(queryPoints[i], queryCovariances[i]).cost;
    }
    const double treeSeconds = secondsSince(start);
    const double facesPerQuery =
      static_cast<double>(MeshTree::facesVisited() - facesBefore) / queries;
    // As in a registration's later iterations: the previous match as the hint.
    std::vector<int> hints(queries);
    for (int i = 0; i < queries; ++i)
    {
      hints[i] =
        model.tree().mostLikelyPoint(queryPoints[i], queryCovariances[i]).surfacePoint.face;
    }
    const long long hintedBefore = MeshTree::facesVisited();
    for (int i = 0; i < queries; ++i)
    {
      checksum += model.tree().mostLikelyPoint(queryPoints[i], queryCovariances[i], hints[i]).cost;
    }
    const double hintedFacesPerQuery =
      static_cast<double>(MeshTree::facesVisited() - hintedBefore) / queries;
    checksum /= 2.0;
    start = Clock::now();
    for (int i = 0; i < queries; ++i)
    {
      checksum -=
        MeshTree::mostLikelyPointBruteForce(mesh, queryPoints[i], queryCovariances[i]).cost;
    }
    const double bruteSeconds = secondsSince(start);
    std::printf("most likely point: tree %.1f us (%.1f faces; %.1f from the previous match), "
                "brute force %.1f us per query: speed-up %.0fx (checksum %.1e)\n",
      1e6 * treeSeconds / queries, facesPerQuery, hintedFacesPerQuery, 1e6 * bruteSeconds / queries,
      bruteSeconds / treeSeconds, checksum);
    out["mlp_tree_speedup"] = bruteSeconds / treeSeconds;
    out["mlp_faces_per_query"] = facesPerQuery;
    out["mlp_faces_per_query_from_previous_match"] = hintedFacesPerQuery;
    out["mesh_triangles"] = mesh.numberOfFaces();
    if (!jsonPath.empty())
    {
      std::ofstream(jsonPath) << out.dump(2) << "\n";
    }
  }
  catch (const Error& e)
  {
    std::fprintf(stderr, "benchmark: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
