#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Evaluation/Peers/Open3DPeers.h>
#include <vimlop/Evaluation/SyntheticProtocol.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace vimlop;

namespace
{

/// Three small trials of our methods on a cavity built in memory.
SyntheticProtocolOptions smallRun()
{
  SyntheticProtocolOptions o;
  o.trials = 3;
  o.synthetic.points = 400; // a smaller model than an airway needs fewer
  o.methods = { "vimlop", "imlp", "trimmed-icp" };
  return o;
}

std::string errorOf(const TriangleMesh& mesh, const SyntheticProtocolOptions& o,
  const EvaluationProgress& progress = EvaluationProgress())
{
  try
  {
    runSyntheticProtocol(mesh, o, progress);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(SyntheticProtocol, RegistersThreeTrialsOfTheCavityToATenthOfAMillimetre)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  std::vector<int> counted;
  const SyntheticProtocolReport r = runSyntheticProtocol(mesh, smallRun(),
    [&](const std::string& what, int done, int total)
    {
      EXPECT_EQ(what, "P1: trial");
      EXPECT_EQ(total, 3);
      counted.push_back(done);
      return true;
    });
  EXPECT_EQ(counted, (std::vector<int>{ 1, 2, 3 }));
  ASSERT_EQ(r.methods.size(), 3u);
  EXPECT_EQ(r.methods[0].method, "vimlop");
  EXPECT_EQ(r.trials, 3);
  EXPECT_EQ(r.meshTriangles, mesh.numberOfFaces());
  EXPECT_LT(r.methods[0].treMedianMm, 0.3);
  EXPECT_LT(r.methods[0].treP95Mm, 0.5);
  EXPECT_DOUBLE_EQ(r.methods[0].successRate, 1.0);
  EXPECT_LT(r.methods[0].cameraPositionMedianMm, 0.5);
  EXPECT_LE(r.methods[0].treMeanMm, r.methods[2].treMeanMm + 0.05);

  // The JSON holds the same numbers under the keys the user guide lists.
  const nlohmann::json j = r.toJson();
  EXPECT_EQ(j["protocol"], "P1");
  EXPECT_EQ(j["trials"], 3);
  EXPECT_EQ(j["methods"]["vimlop"]["tre_mm"]["median"].get<double>(), r.methods[0].treMedianMm);
  EXPECT_EQ(j["methods"]["imlp"]["success_rate"].get<double>(), r.methods[1].successRate);
  EXPECT_TRUE(j["methods"]["trimmed-icp"]["runtime_s"].contains("p95"));
}

TEST(SyntheticProtocol, GivesTheSameFiguresForTheSameSeed)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  SyntheticProtocolOptions o = smallRun();
  o.trials = 1;
  o.methods = { "vimlop" };
  const SyntheticProtocolReport a = runSyntheticProtocol(mesh, o, EvaluationProgress());
  o.threads = 1;
  const SyntheticProtocolReport b = runSyntheticProtocol(mesh, o, EvaluationProgress());
  EXPECT_EQ(a.methods[0].treMeanMm, b.methods[0].treMeanMm);
  o.seed = 2;
  const SyntheticProtocolReport c = runSyntheticProtocol(mesh, o, EvaluationProgress());
  EXPECT_NE(a.methods[0].treMeanMm, c.methods[0].treMeanMm);
}

TEST(SyntheticProtocol, KeepsThePapersRegistrationSettingsOfItsOwn)
{
  // P1 does not follow RegistrationOptions' defaults (the video ones): its
  // figures are those of the paper's settings.
  const SyntheticProtocolOptions o;
  EXPECT_EQ(o.contourVariancePx2, 9.0);
  EXPECT_EQ(o.kappa, 200.0);
  EXPECT_EQ(o.stallRelativeDecrease, 1e-3);
  EXPECT_EQ(o.stallIterations, 5);
  EXPECT_EQ(o.maxIterations, 100);
  EXPECT_EQ(o.minScale, 0.8);
  EXPECT_EQ(o.maxScale, 1.25);
}

TEST(SyntheticProtocol, RefusesUnknownRepeatedOrMissingMethodsAndNoTrials)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  SyntheticProtocolOptions o = smallRun();
  o.methods = { "vimlop", "magic" };
  EXPECT_EQ(errorOf(mesh, o),
    "unknown method 'magic' (expected vimlop, imlp, trimmed-icp, open3d-icp, open3d-gicp, "
    "open3d-icp-prebuilt, open3d-gicp-prebuilt)");
  o.methods = { "imlp", "vimlop", "imlp" };
  EXPECT_EQ(errorOf(mesh, o), "method 'imlp' is listed twice");
  o = smallRun();
  o.trials = 0;
  EXPECT_EQ(errorOf(mesh, o), "the number of trials must be at least 1");
  o = smallRun();
  o.methods = { "open3d-icp" };
  o.saveTrialFolder = "unused";
  EXPECT_EQ(errorOf(mesh, o),
    Open3DPeers::available()
      ? "--save-trial needs one of the methods vimlop, imlp, trimmed-icp"
      : "method 'open3d-icp' needs Open3D, which this build of VIMLOP lacks");
}

TEST(SyntheticProtocol, OpenThreeDWithItsTargetTreeBuiltOnceGivesTheEstimateOfItsOwnCall)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  if (!Open3DPeers::available())
  {
    EXPECT_THROW(Open3DPeers peers(mesh), Error);
    return;
  }
  const RegistrationModel model(mesh);
  SyntheticOptions synthetic;
  synthetic.points = 400;
  const SyntheticTrial trial = makeSyntheticTrial(model, synthetic, 3);
  const Open3DPeers peers(mesh);
  using Tree = Open3DPeers::TargetTree;
  const SimilarityTransform icp =
    peers.icpWithScale(trial.data.points, trial.initialSfmToCT, Tree::PerCall);
  const SimilarityTransform icpPrebuilt =
    peers.icpWithScale(trial.data.points, trial.initialSfmToCT, Tree::Prebuilt);
  const SimilarityTransform gicp =
    peers.generalizedIcp(trial.data.points, trial.initialSfmToCT, Tree::PerCall);
  const SimilarityTransform gicpPrebuilt =
    peers.generalizedIcp(trial.data.points, trial.initialSfmToCT, Tree::Prebuilt);
  // The same iterations; only the order of Open3D's parallel sums differs.
  EXPECT_LT((icp.matrix() - icpPrebuilt.matrix()).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((gicp.matrix() - gicpPrebuilt.matrix()).cwiseAbs().maxCoeff(), 1e-6);
  // And they did register: nearer the truth than the start.
  const double before =
    (trial.initialSfmToCT.matrix() - trial.truthSfmToCT.matrix()).cwiseAbs().maxCoeff();
  EXPECT_LT((icpPrebuilt.matrix() - trial.truthSfmToCT.matrix()).cwiseAbs().maxCoeff(), before);
}

TEST(SyntheticProtocol, StopsWhenTheProgressCallbackCancels)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  SyntheticProtocolOptions o = smallRun();
  o.methods = { "trimmed-icp" };
  int calls = 0;
  EXPECT_EQ(errorOf(mesh, o,
              [&](const std::string&, int, int)
              {
                ++calls;
                return false;
              }),
    "P1: trial: cancelled");
  EXPECT_EQ(calls, 1);
}
