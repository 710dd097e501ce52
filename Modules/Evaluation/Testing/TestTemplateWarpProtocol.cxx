#include "AirwayPhantom.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/TemplateWarpProtocol.h>

#include <gtest/gtest.h>

#include <string>

using namespace vimlop;
using fixtures::HeadPhantom;

namespace
{

/// P4 on the phantom head: a small field, finer levels than a CT needs.
TemplateWarpProtocolOptions phantomRun()
{
  TemplateWarpProtocolOptions o;
  o.maxDisplacementMm = 3.0;
  o.controlSpacingMm = 24.0;
  o.noiseHU = 10.0;
  o.seed = 3;
  o.runElastix = false;
  o.registration.marginMm = 10.0;
  o.registration.affineLevelSpacingMm = { 2.0, 1.0 };
  o.registration.synLevelSpacingMm = { 2.0, 1.0 };
  o.registration.synIterations = { 30, 20 };
  return o;
}

std::string errorOf(const TemplateWarpProtocolOptions& o)
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

TEST(TemplateWarpProtocol, BringsThePhantomsAirwayOntoAKnownDeformationOfIt)
{
  int last = -1;
  bool monotone = true;
  const TemplateWarpProtocolReport r = runTemplateWarpProtocol(HeadPhantom::make(), phantomRun(),
    [&](const std::string&, int done, int total)
    {
      EXPECT_EQ(total, 1000);
      monotone = monotone && done >= last;
      last = done;
      return true;
    });
  EXPECT_TRUE(monotone);
  EXPECT_EQ(last, 1000);
  EXPECT_GT(r.vertices, 100u);
  EXPECT_GT(r.beforeRegistration.meanMm, 1.0);
  EXPECT_LT(r.errors.meanMm, 0.5);
  EXPECT_LT(r.errors.p95Mm, 1.0);
  EXPECT_LE(r.errors.p95Mm, r.errors.maxMm);
  EXPECT_GT(r.finalCorrelation, 0.9);
  EXPECT_FALSE(r.elastix);
  EXPECT_EQ(r.elastixStatus, "not run (--no-elastix)");

  const nlohmann::json j = r.toJson();
  EXPECT_EQ(j["mean_mm"].get<double>(), r.errors.meanMm);
  EXPECT_EQ(j["before_registration"]["mean_mm"].get<double>(), r.beforeRegistration.meanMm);
  EXPECT_EQ(j["registration"]["correlation"]["final"].get<double>(), r.finalCorrelation);
  EXPECT_TRUE(j["elastix"].is_null());
}

TEST(TemplateWarpProtocol, RefusesANonPositiveDisplacementNegativeNoiseOrNoElastixFolder)
{
  TemplateWarpProtocolOptions o = phantomRun();
  o.maxDisplacementMm = 0.0;
  EXPECT_EQ(errorOf(o), "--max-displacement-mm must be positive");
  o = phantomRun();
  o.noiseHU = -1.0;
  EXPECT_EQ(errorOf(o), "--noise-hu must not be negative");
  o = phantomRun();
  o.runElastix = true;
  EXPECT_EQ(errorOf(o), "P4: elastix needs a work folder");
}
