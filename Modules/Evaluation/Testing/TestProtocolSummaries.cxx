// The summary lines of the typed reports of P1-P4: what `vimlop evaluate`
// prints, and what any other face can print alike.
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/PerturbationProtocol.h>
#include <vimlop/Evaluation/SyntheticProtocol.h>
#include <vimlop/Evaluation/TemplateWarpProtocol.h>
#include <vimlop/Evaluation/TrackingProtocol.h>
#include <vimlop/Evaluation/VideoProtocol.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace vimlop;

TEST(ProtocolSummaries, SyntheticGivesOneLinePerMethod)
{
  SyntheticProtocolReport report;
  SyntheticProtocolMethodReport m;
  m.method = "vimlop";
  m.treMedianMm = 0.1234;
  m.treMeanMm = 0.2;
  m.treP95Mm = 0.5;
  m.successRate = 1.0;
  m.cameraPositionMedianMm = 0.25;
  m.cameraAngleMedianDeg = 0.5;
  m.runtimeMedianS = 1.5;
  report.methods = { m, m };
  report.methods[1].method = "imlp";
  report.methods[1].successRate = 0.5;
  const std::vector<std::string> lines = report.summaryLines();
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0],
    "P1 vimlop               TRE median 0.123 mm (mean 0.200, p95 0.500), success 100 %, camera "
    "0.250 mm "
    "/ 0.500 deg, runtime median 1.500 s");
  const std::string imlp = "P1 " + std::string("imlp").append(16, ' ') + " TRE median 0.123 mm";
  EXPECT_EQ(lines[1].substr(0, imlp.size()), imlp);
  EXPECT_NE(lines[1].find("success 50 %"), std::string::npos);
}

TEST(ProtocolSummaries, VideoGivesContoursThenEachMethodAndItsMultiStart)
{
  VideoProtocolReport report;
  report.sfm = "builtin";
  report.sfmPoints = 812;
  report.contours.precision = 0.9;
  report.contours.recall = 0.8;
  report.contours.normalErrorDegMedian = 12.34;
  report.candidates = 42;
  VideoProtocolMethodReport vimlop;
  vimlop.method = "vimlop";
  vimlop.errors.positionMeanMm = 0.5;
  vimlop.errors.positionMaxMm = 1.0;
  vimlop.errors.angleMeanDeg = 2.0;
  vimlop.errors.angleMaxDeg = 3.0;
  vimlop.errors.scaleErrorRel = 0.0123;
  vimlop.errors.runtimeS = 4.56;
  vimlop.multiStart = VideoMultiStartFigures();
  vimlop.multiStart->contourErrorPx = 1.234;
  VideoProtocolMethodReport imlp = vimlop;
  imlp.method = "imlp";
  imlp.multiStart->failureFlag = true;
  report.methods = { vimlop, imlp };
  const std::vector<std::string> lines = report.summaryLines();
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0],
    "P2 contours: precision 0.900, recall 0.800, median normal error 12.3 deg; SfM (builtin) 812 "
    "points");
  EXPECT_EQ(lines[1],
    "P2 vimlop camera 0.500 mm (max 1.000) / 2.000 deg (max 3.000), scale error 1.23 %, runtime "
    "4.6 s");
  EXPECT_EQ(lines[2], "P2 vimlop multi-start of 42 candidates: contour error 1.23 px, not flagged");
  EXPECT_EQ(lines[3].substr(0, 10), "P2 imlp   ");
  EXPECT_EQ(lines[4],
    "P2 imlp   multi-start of 42 candidates: contour error 1.23 px, FLAGGED as a failure");

  report.methods[0].multiStart.reset();
  report.methods.pop_back();
  EXPECT_EQ(report.summaryLines().size(), 2u);
}

TEST(ProtocolSummaries, PerturbationGivesEachOffsetThenTheRocArea)
{
  PerturbationProtocolReport report;
  PerturbationOffsetReport offset;
  offset.offsetMm = 2.0;
  offset.offsetDeg = 2.0;
  offset.successRate = 0.9;
  offset.cameraPositionMedianMm = 0.4567;
  offset.contourErrorMedianPx = 1.5;
  report.offsets = { offset };
  std::vector<std::string> lines = report.summaryLines();
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0],
    "P3 offset  2.0 mm /  2.0 deg: success  90 %, camera error median 0.457 mm, contour error "
    "median 1.50 px");
  EXPECT_EQ(lines[1], "P3 every run succeeded; no ROC area (it needs both successes and failures)");
  report.failures = 10;
  EXPECT_EQ(report.summaryLines()[1],
    "P3 every run failed; no ROC area (it needs both successes and failures)");
  report.failures = 3;
  report.runsTotal = 20;
  report.auc = 0.95;
  report.failureThresholdPx = 2.5;
  EXPECT_EQ(report.summaryLines()[1],
    "P3 contour error separates failures from successes: ROC AUC 0.950, best threshold 2.50 px (3 "
    "failures of 20 runs)");
}

TEST(ProtocolSummaries, TemplateWarpGivesOursThenElastixAndChecksTheBounds)
{
  TemplateWarpProtocolReport report;
  report.seed = 2;
  report.maxDisplacementMm = 5.0;
  report.errors.meanMm = 0.5;
  report.errors.p95Mm = 1.25;
  report.errors.maxMm = 2.0;
  report.runtimeS = 12.34;
  report.beforeRegistration.meanMm = 3.0;
  EXPECT_EQ(report.summaryText(),
    "seed 2, 5.0 mm: mean 0.50 mm, p95 1.25 mm, max 2.00 mm, 12.3 s (before: mean 3.00 mm)");
  report.elastix = TemplateWarpProtocolReport::Elastix();
  report.elastix->errors.meanMm = 0.75;
  report.elastix->runtimeS = 30.0;
  report.elastix->runtimeRatio = 2.43;
  EXPECT_NE(report.summaryText().find(
              "; elastix mean 0.75 mm, p95 0.00 mm, max 0.00 mm, 30.0 s (2.43x our time)"),
    std::string::npos);

  EXPECT_NO_THROW(report.requireErrorsAtMost(-1.0, -1.0));
  EXPECT_NO_THROW(report.requireErrorsAtMost(0.5, 1.25));
  try
  {
    report.requireErrorsAtMost(0.4, -1.0);
    FAIL() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "the mean vertex error 0.50 mm exceeds the required 0.40 mm");
  }
  try
  {
    report.requireErrorsAtMost(1.0, 1.0);
    FAIL() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "the 95th percentile vertex error 1.25 mm exceeds the required 1.00 mm");
  }
}

TEST(ProtocolSummaries, TemplateWarpComparesItsMeanAndRuntimeWithElastixs)
{
  TemplateWarpProtocolReport report;
  report.errors.meanMm = 0.10;
  report.runtimeS = 8.0;
  report.elastixStatus = "not installed";
  auto errorOf = [&]
  {
    try
    {
      report.requireNoWorseThanElastix();
    }
    catch (const Error& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(errorOf(), "elastix did not run (not installed): nothing to compare with");
  report.elastix = TemplateWarpProtocolReport::Elastix();
  report.elastix->errors.meanMm = 0.12;
  report.elastix->runtimeS = 16.0;
  report.elastix->runtimeRatio = 2.0;
  EXPECT_EQ(errorOf(), "");
  report.elastix->errors.meanMm = 0.09;
  EXPECT_EQ(errorOf(), "the mean vertex error 0.100 mm exceeds elastix's 0.090 mm");
  report.elastix->errors.meanMm = 0.12;
  report.elastix->runtimeS = 6.0;
  report.elastix->runtimeRatio = 0.75;
  EXPECT_EQ(errorOf(), "the registration took 8.0 s, longer than elastix's 6.0 s");
}

TEST(ProtocolSummaries, TrackingEndsWithTheTrackersLagOnlyWhenItHadATracker)
{
  TrackingProtocolReport report;
  report.frames = 600;
  report.registrationFrames = 30;
  ASSERT_EQ(report.summaryLines().size(), 4u);
  report.trackerPrior = true;
  EXPECT_EQ(report.summaryLines().back(), "tracking: the video measured no lag of the tracker");
  report.trackerLagS = 0.0795;
  report.trackerLagPairs = 270;
  ASSERT_EQ(report.summaryLines().size(), 5u);
  EXPECT_EQ(report.summaryLines().back(),
    "tracking: the tracker's lag, as the video's motion showed it: 79.5 ms (270 pairs of frames)");
  EXPECT_EQ(report.toJson()["tracker_lag"]["lag_s"].get<double>(), 0.0795);
  EXPECT_EQ(report.toJson()["tracker_lag"]["pairs"].get<int>(), 270);
}
