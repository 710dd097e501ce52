#include "CraniumAirway.h"
#include "ErrorMessage.h"
#include "TestFolders.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/ErrorBudgetProtocol.h>
#include <vimlop/Imaging/CTVolumeIO.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <tuple>

using namespace vimlop;

namespace
{

std::string errorOf(const ErrorBudgetOptions& o)
{
  return fixtures::errorMessageOf([&] { o.validate(); });
}

} // namespace

TEST(ErrorBudgetProtocol, RefusesSettingsItCannotRun)
{
  ErrorBudgetOptions o;
  EXPECT_EQ(errorOf(o), "P5: a work folder is required");
  o.workFolder = "work";
  EXPECT_EQ(errorOf(o), "no error");
  ErrorBudgetOptions bad = o;
  bad.seeds = 0;
  EXPECT_EQ(errorOf(bad), "P5: --seeds must be at least 1");
  bad = o;
  bad.sources = { "weather" };
  EXPECT_EQ(errorOf(bad).rfind("unknown error source 'weather' (expected one of anatomy,", 0), 0u);
  bad = o;
  bad.levels = { 0.5, 5.0 };
  EXPECT_EQ(errorOf(bad), "P5: each level must lie in (0, 4], not 5");
  bad = o;
  bad.canonicalStarts = bad.perturbedStarts = false;
  EXPECT_EQ(errorOf(bad), "P5: neither canonical nor perturbed starts");
  bad = o;
  bad.goodMm = 2.0; // above the success threshold, 1 mm
  EXPECT_EQ(
    errorOf(bad), "P5: the good threshold must be positive and at most the success threshold");
}

TEST(ErrorBudgetProtocol, PoolsTheFailureFlagOverConditionsAndStarts)
{
  // camera error mm, contour error px, flagged
  const std::vector<std::tuple<double, double, bool>> outcomes = {
    { 0.2, 1.0, false }, // good
    { 0.3, 8.0, true },  // good, flagged: a false flag
    { 0.7, 2.0, true },  // neither good nor a failure
    { 2.0, 3.0, false }, // a failure missed
    { 5.0, 20.0, true }, // a failure caught
  };
  ErrorBudgetReport report;
  for (const auto& [mm, px, flagged] : outcomes)
  {
    BudgetRegistration r;
    r.condition = mm < 1.0 ? "ideal" : "anatomy";
    r.start = px > 5.0 ? "canonical" : "perturbed";
    r.method = "vimlop";
    r.cameraPositionMm = mm;
    r.contourErrorPx = px;
    r.flagged = flagged;
    report.registrations.push_back(r);
  }
  report.registrations.push_back(report.registrations.front());
  report.registrations.back().method = "imlp";

  const FailureFlagFigures f = report.failureFlag().at("vimlop");
  EXPECT_EQ(f.registrations, 5);
  EXPECT_EQ(f.failures, 2);
  EXPECT_EQ(f.missed, 1);
  EXPECT_EQ(f.good, 2);
  EXPECT_EQ(f.falseFlags, 1);
  // Failures at 3 and 20 px against successes at 1, 8 and 2 px: 5 of 6 pairs ordered.
  ASSERT_TRUE(f.contourErrorAuc);
  EXPECT_NEAR(*f.contourErrorAuc, 5.0 / 6.0, 1e-12);
  // IMLP's one good registration: no failure, no AUC.
  const FailureFlagFigures imlp = report.failureFlag().at("imlp");
  EXPECT_EQ(imlp.registrations, 1);
  EXPECT_FALSE(imlp.contourErrorAuc);

  const nlohmann::json j = report.toJson();
  ASSERT_EQ(j["registrations"].size(), 6u);
  EXPECT_EQ(j["registrations"][3]["camera_position_mm"], 2.0);
  EXPECT_EQ(j["registrations"][3]["start"], "perturbed");
  EXPECT_EQ(j["failure_flag"]["good_mm"], 0.5);
  EXPECT_EQ(j["failure_flag"]["methods"]["vimlop"]["missed"], 1);
  EXPECT_EQ(j["failure_flag"]["methods"]["vimlop"]["false_flags"], 1);
  EXPECT_TRUE(j["failure_flag"]["methods"]["imlp"]["contour_error_auc"].is_null());
  const std::vector<std::string> lines = report.summaryLines();
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[1],
    "P5 failure flag vimlop      5 registrations pooled: missed 1 of 2 failures (50 %), flagged "
    "1 of 2 good (50 %), contour error AUC 0.833");
}

TEST(ErrorBudgetProtocol, ReportsInTheLayoutOfTheIssue)
{
  ErrorBudgetReport report;
  report.seeds = 2;
  BudgetCondition clinical;
  clinical.name = "clinical";
  BudgetMethodFigures f;
  f.cameraPositionMm = { 0.6, 0.5, 1.2, 1.5 };
  f.successRate = 0.5;
  f.failureAuc = 0.75;
  clinical.canonical["vimlop"] = f;
  f.failureAuc.reset();
  clinical.perturbed["imlp"] = f;
  BudgetCondition lens;
  lens.name = "lens";
  lens.source = "lens";
  lens.knob = "k1";
  lens.value = -0.35;
  report.conditions = { clinical, lens };
  const nlohmann::json j = report.toJson();
  EXPECT_EQ(j["protocol"], "P5");
  EXPECT_EQ(j["seeds"], 2);
  const nlohmann::json& v = j["conditions"]["clinical"]["methods"]["vimlop"];
  EXPECT_EQ(v["camera_position_mm"]["median"], 0.5);
  EXPECT_EQ(v["camera_position_mm"]["p95"], 1.2);
  EXPECT_EQ(v["failure_auc"], 0.75);
  EXPECT_EQ(v["success_rate"], 0.5);
  for (const char* key : { "camera_angle_deg", "tre_mm" })
  {
    EXPECT_TRUE(v.contains(key)) << key;
  }
  EXPECT_TRUE(
    j["conditions"]["clinical"]["perturbed_start"]["methods"]["imlp"]["failure_auc"].is_null());
  EXPECT_EQ(j["conditions"]["lens"]["value"], -0.35);
  EXPECT_FALSE(j["conditions"]["clinical"].contains("source"));
  const std::vector<std::string> lines = report.summaryLines();
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0].rfind("P5 clinical       vimlop      camera 0.500 mm (p95 1.200)", 0), 0u)
    << lines[0];
}

// Under a display: a small budget end to end on the bundled CT.
TEST(ErrorBudgetProtocolOnTheCranium, RegistersEachConditionFromTheUsersFilesAlone)
{
  ErrorBudgetOptions o;
  o.seeds = 1;
  o.frames = 6;
  o.sources = { "tracker" };
  o.clinical = false;
  o.methods = { RegistrationMethod::VIMLOP, RegistrationMethod::TrimmedICP };
  o.canonicalStarts = false;
  o.workFolder = fixtures::freshTestFolder("p5-work").string();
  int sequences = 0;
  const ErrorBudgetReport r = runErrorBudgetProtocol(readCTVolume(fixtures::craniumPath()), o,
    [&](const std::string& what, int done, int total)
    {
      sequences += what == "P5: sequence" && done > 0 && total == 2;
      return true;
    });
  EXPECT_EQ(sequences, 2);
  ASSERT_EQ(r.conditions.size(), 2u);
  // Every registration is on record: 2 conditions, 1 seed, 2 methods.
  ASSERT_EQ(r.registrations.size(), 4u);
  for (const BudgetRegistration& g : r.registrations)
  {
    EXPECT_EQ(g.start, "perturbed");
    EXPECT_FALSE(g.rivalContourErrorPx) << "a single start has no rival";
    EXPECT_EQ(g.seed, 1u);
    EXPECT_GT(g.cameraPositionMm, 0.0);
    EXPECT_GE(g.matchedFraction, g.method == "vimlop" ? 0.5 : 0.0) << g.method;
    EXPECT_LE(g.matchedFraction, 1.0);
    // The measures a confidence could use, from a good registration.
    EXPECT_GT(g.pointInlierFraction, 0.5);
    EXPECT_LE(g.pointInlierFraction, 1.0);
    EXPECT_GT(g.residualErrorMm, 0.0);
    if (g.method == "vimlop")
    {
      EXPECT_GT(g.contourInlierFraction, 0.5);
      EXPECT_LE(g.contourInlierFraction, 1.0);
      EXPECT_GT(g.frameContourErrorMedianPx, 0.0);
      EXPECT_LE(g.frameContourErrorMedianPx, g.frameContourErrorMaxPx);
    }
  }
  EXPECT_EQ(r.registrations[0].condition, "ideal");
  EXPECT_EQ(r.registrations[1].method, "trimmed-icp");
  EXPECT_EQ(r.registrations[3].condition, "tracker");
  EXPECT_EQ(r.conditions[0].name, "ideal");
  EXPECT_EQ(r.conditions[1].name, "tracker");
  EXPECT_EQ(r.conditions[1].value, 0.03);
  for (const BudgetCondition& c : r.conditions)
  {
    EXPECT_TRUE(c.failedSequences.empty()) << c.name << ": " << c.failedSequences.front();
    ASSERT_EQ(c.perturbed.count("vimlop"), 1u) << c.name;
    const BudgetMethodFigures& v = c.perturbed.at("vimlop");
    EXPECT_EQ(v.registrations, 1);
    // Ideal or with a late tracker, six frames register to within a millimetre.
    EXPECT_LT(v.cameraPositionMm.median, 1.0) << c.name;
    EXPECT_GT(c.floorPositionMm.median, 0.0);
    EXPECT_EQ(c.canonical.size(), 0u);
  }
  // The pipeline read the user's files; the truth was never beside them.
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(o.workFolder) / "sequence" / "frames"));
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(o.workFolder) / "sequence" / "truth"));
}
