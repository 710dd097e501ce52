#include "CraniumAirway.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/PerturbationProtocol.h>

#include <gtest/gtest.h>

#include <string>

using namespace vimlop;

namespace
{

std::string errorOf(const PerturbationProtocolOptions& o)
{
  try
  {
    o.validate();
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(PerturbationProtocol, SucceedsFromTheTruthOnEightSimulatedFrames)
{
  PerturbationProtocolOptions o;
  o.video.simulation.frames = 8;
  o.offsets = { 0.0, 10.0 };
  o.trialsPerOffset = 1;
  int runs = 0;
  const PerturbationProtocolReport r = runPerturbationProtocol(fixtures::craniumAirwayMesh(), o,
    [&](const std::string& what, int, int)
    {
      runs += what.rfind("P3: run ", 0) == 0;
      return true;
    });
  EXPECT_EQ(runs, 2);
  ASSERT_EQ(r.offsets.size(), 2u);
  ASSERT_EQ(r.runs.size(), 2u);
  EXPECT_EQ(r.runsTotal, 2);
  EXPECT_DOUBLE_EQ(r.offsets[0].successRate, 1.0);
  EXPECT_LT(r.offsets[0].cameraPositionMedianMm, 1.0);
  EXPECT_EQ(r.runs[1].offsetMm, 10.0);
  EXPECT_EQ(r.failures, r.runs[1].success ? 0u : 1u);
  // One success and one failure give an ROC area; two successes none.
  EXPECT_EQ(r.auc.has_value(), r.failures == 1u);

  const nlohmann::json j = r.toJson();
  EXPECT_EQ(j["protocol"], "P3");
  EXPECT_EQ(j["offsets"][0]["success_rate"].get<double>(), 1.0);
  EXPECT_EQ(j["auc"].is_null(), !r.auc);
}

TEST(PerturbationProtocol, RefusesNoOffsetsOffsetsBeyondNinetyAndNoSuccessBound)
{
  PerturbationProtocolOptions o;
  o.offsets.clear();
  EXPECT_EQ(errorOf(o), "P3: need at least one offset and one trial per offset");
  o.offsets = { 0.0, 120.0 };
  EXPECT_EQ(errorOf(o), "P3: offsets must lie in [0, 90] (mm and degrees), got 120.000000");
  o.offsets = { 1.0 };
  o.successMm = 0.0;
  EXPECT_EQ(errorOf(o), "P3: the success bound must be positive");
}
