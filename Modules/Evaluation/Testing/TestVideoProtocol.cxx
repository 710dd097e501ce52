#include "CraniumAirway.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/VideoProtocol.h>

#include <gtest/gtest.h>

#include <string>

using namespace vimlop;

namespace
{

std::string errorOf(const VideoProtocolOptions& o)
{
  try
  {
    runVideoProtocol(TriangleMesh(), o, EvaluationProgress());
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(VideoProtocol, RegistersTwelveSimulatedFramesOfTheCraniumToHalfAMillimetre)
{
  VideoProtocolOptions o;
  o.simulation.frames = 12;
  o.simulation.seed = 1;
  int framesRendered = 0;
  bool sawSfm = false;
  const VideoProtocolReport r = runVideoProtocol(fixtures::craniumAirwayMesh(), o,
    [&](const std::string& what, int done, int total)
    {
      framesRendered += what == "simulate: frame" && total == 12 && done > 0;
      sawSfm = sawSfm || what.rfind("sfm: ", 0) == 0;
      return true;
    });
  EXPECT_EQ(framesRendered, 12);
  EXPECT_TRUE(sawSfm);
  EXPECT_GT(r.contours.precision, 0.8);
  EXPECT_GT(r.contours.recall, 0.8);
  EXPECT_GT(r.sfmPoints, 100u);
  ASSERT_EQ(r.methods.size(), 2u);
  EXPECT_EQ(r.methods[0].method, "vimlop");
  EXPECT_LT(r.methods[0].errors.positionMeanMm, 0.5);
  EXPECT_LT(r.methods[0].errors.angleMeanDeg, 0.5);
  EXPECT_LT(r.methods[0].errors.scaleErrorRel, 0.05);
  EXPECT_FALSE(r.methods[0].multiStart);
  EXPECT_FALSE(r.candidates);

  const nlohmann::json j = r.toJson();
  EXPECT_EQ(j["protocol"], "P2");
  EXPECT_EQ(j["frames"], 12);
  EXPECT_EQ(j["methods"]["vimlop"]["camera_position_mm"]["mean"].get<double>(),
    r.methods[0].errors.positionMeanMm);
  EXPECT_EQ(j["sfm_floor"]["runtime_s"].get<double>(), 0.0);
  EXPECT_FALSE(j.contains("candidates"));
}

TEST(VideoProtocol, RefusesAnUnknownStartOrStructureFromMotion)
{
  VideoProtocolOptions o;
  o.init = "lucky";
  EXPECT_EQ(errorOf(o), "--init: expected 'perturbed' or 'canonical', got 'lucky'");
  o.init = "perturbed";
  o.sfm = "magic";
  EXPECT_EQ(errorOf(o), "--sfm: expected 'builtin' or 'colmap', got 'magic'");
}
