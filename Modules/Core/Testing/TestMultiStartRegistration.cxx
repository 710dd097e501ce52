#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/MultiStartRegistration.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/SyntheticExperiment.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace vimlop;

namespace
{

const RegistrationModel& cavityModel()
{
  static const RegistrationModel model(fixtures::makeCavityWithBlobs());
  return model;
}

SyntheticTrial trial(std::uint64_t seed)
{
  SyntheticOptions o;
  o.points = 400;
  return makeSyntheticTrial(cavityModel(), o, seed);
}

MultiStartOptions options()
{
  MultiStartOptions o;
  o.registration.minScale = 0.8;
  o.registration.maxScale = 1.25;
  o.screeningIterations = 6;
  o.finalists = 1;
  return o;
}

/// The trial's start turned by `degrees` about the z axis through the
/// centroid of its cameras: far off when large.
SimilarityTransform turned(const SyntheticTrial& t, double degrees)
{
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const VideoFrame& f : t.data.frames)
  {
    centre += t.initialSfmToCT.apply(f.cameraToSfm.centre);
  }
  centre /= static_cast<double>(t.data.frames.size());
  SimilarityTransform turn;
  turn.rotation = rotationFromVector(degrees * M_PI / 180.0 * Eigen::Vector3d::UnitZ());
  turn.translation = centre - turn.rotation * centre;
  return turn.compose(t.initialSfmToCT);
}

} // namespace

TEST(MultiStartRegistration, StartFromCameraPosePlacesTheFrame)
{
  CameraPose inCT;
  inCT.rotation = rotationFromVector(Eigen::Vector3d(0.3, -0.2, 0.5));
  inCT.centre = Eigen::Vector3d(4, 5, 6);
  CameraPose inSfm;
  inSfm.rotation = rotationFromVector(Eigen::Vector3d(-0.1, 0.4, 0.2));
  inSfm.centre = Eigen::Vector3d(-1, 2, 0.5);
  const SimilarityTransform t = startFromCameraPose(inCT, inSfm, 2.5);
  EXPECT_DOUBLE_EQ(t.scale, 2.5);
  EXPECT_LT((t.apply(inSfm).matrix() - inCT.matrix()).norm(), 1e-12);
}

TEST(MultiStartRegistration, TheLeastContourErrorWinsWhateverTheThreads)
{
  const SyntheticTrial t = trial(11);
  // A hopeless start first, the trial's own start second.
  const std::vector<SimilarityTransform> starts = { turned(t, 70.0), t.initialSfmToCT };
  MultiStartOptions one = options();
  one.threads = 1;
  MultiStartOptions two = one;
  two.threads = 2;
  const MultiStartResult a = registerMultiStart(cavityModel(), t.data, starts, one);
  const MultiStartResult b = registerMultiStart(cavityModel(), t.data, starts, two);
  ASSERT_EQ(a.candidates.size(), 6u);
  EXPECT_EQ(a.candidates[a.bestCandidate].start, 1);
  EXPECT_LT(targetRegistrationError(a.best.sfmToCT, t.truthSfmToCT, t.targetsCT), 0.5);
  EXPECT_FALSE(a.failure);
  // Screening kept one start, which then ran at its three scale factors;
  // the winner's error is the least of them.
  int finalists = 0;
  for (const MultiStartCandidate& c : a.candidates)
  {
    finalists += c.finalist;
    EXPECT_EQ(c.finalist, c.start == 1);
    if (c.finalist)
    {
      EXPECT_GE(c.contourErrorPx, a.best.contourErrorPx);
    }
  }
  EXPECT_EQ(finalists, 3);
  // Only the factor-1 candidates were screened.
  EXPECT_GT(a.candidates[1].screeningContourErrorPx, 0.0);
  EXPECT_EQ(a.candidates[0].screeningContourErrorPx, 0.0);
  EXPECT_EQ(a.bestCandidate, b.bestCandidate);
  EXPECT_EQ(a.best.sfmToCT.matrix(), b.best.sfmToCT.matrix());
  // Each candidate that ran keeps where it ended: the winner where the result is.
  EXPECT_EQ(a.candidates[a.bestCandidate].finalSfmToCT.matrix(), a.best.sfmToCT.matrix());
  EXPECT_NE(a.candidates[0].finalSfmToCT.matrix(), a.candidates[0].initialSfmToCT.matrix());
  for (size_t i = 0; i < a.candidates.size(); ++i)
  {
    EXPECT_EQ(a.candidates[i].contourErrorPx, b.candidates[i].contourErrorPx);
  }
}

TEST(MultiStartRegistration, FlagsFailureSkipsOutsideStartsAndCancels)
{
  const SyntheticTrial t = trial(12);
  SimilarityTransform outside = t.initialSfmToCT;
  outside.translation += Eigen::Vector3d(100.0, 0.0, 0.0);
  MultiStartOptions o = options();
  o.scaleFactors = { 1.0 };
  o.failureContourErrorPx = 1e-6; // nothing fits this well
  const MultiStartResult r =
    registerMultiStart(cavityModel(), t.data, { outside, t.initialSfmToCT }, o);
  ASSERT_EQ(r.candidates.size(), 2u);
  EXPECT_NE(r.candidates[0].skipped.find("starts outside the airway"), std::string::npos);
  EXPECT_EQ(r.bestCandidate, 1);
  EXPECT_TRUE(r.failure);
  EXPECT_EQ(r.failureThresholdPx, 1e-6);
  EXPECT_NE(r.failureReason.find("is above the threshold of 0.00 px"), std::string::npos)
    << r.failureReason;

  try
  {
    registerMultiStart(cavityModel(), t.data, { outside }, o);
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("none of the 1 candidates can start"), std::string::npos)
      << e.what();
  }
  EXPECT_THROW(registerMultiStart(cavityModel(), t.data, {}, o), Error);
  o.scaleFactors = { -1.0 };
  EXPECT_THROW(registerMultiStart(cavityModel(), t.data, { t.initialSfmToCT }, o), Error);

  // Progress sees both phases; returning false cancels.
  o = options();
  std::vector<std::string> phases;
  EXPECT_THROW(registerMultiStart(cavityModel(), t.data, { t.initialSfmToCT, t.initialSfmToCT }, o,
                 [&](const char* phase, int done, int)
                 {
                   phases.emplace_back(phase);
                   return done < 2;
                 }),
    Error);
  ASSERT_FALSE(phases.empty());
  EXPECT_EQ(phases.front(), "screening");
}

TEST(MultiStartRegistration, APoseThatMatchesNoContourIsAFailureNotAPerfectFit)
{
  // A camera facing a wall sees no model contour: nothing is matched and the
  // mean error over the matches is 0 px, which must not read as a success.
  RegistrationResult blind;
  blind.frames.resize(2);
  blind.frames[0].contourPoints = 100;
  blind.frames[1].contourPoints = 50;
  blind.contourErrorPx = 0.0;
  EXPECT_DOUBLE_EQ(matchedContourFraction(blind), 0.0);
  EXPECT_TRUE(isFlaggedAsFailure(blind, MultiStartOptions()));

  RegistrationResult good = blind;
  good.frames[0].matched = 98;
  good.frames[1].matched = 49;
  good.contourErrorPx = 1.5;
  EXPECT_DOUBLE_EQ(matchedContourFraction(good), 147.0 / 150.0);
  EXPECT_FALSE(isFlaggedAsFailure(good, MultiStartOptions()));
  good.contourErrorPx = 4.5; // above the 4 px threshold
  EXPECT_TRUE(isFlaggedAsFailure(good, MultiStartOptions()));
  // Contours that fit while the SfM points stand off the walls: flagged too.
  good.contourErrorPx = 1.5;
  good.residualErrorMm = 0.9; // above the 0.8 mm threshold
  EXPECT_TRUE(isFlaggedAsFailure(good, MultiStartOptions()));
  good.residualErrorMm = 0.7;
  EXPECT_FALSE(isFlaggedAsFailure(good, MultiStartOptions()));
  EXPECT_DOUBLE_EQ(matchedContourFraction(RegistrationResult()), 0.0);
}

TEST(MultiStartRegistration, TheFailureFlagSaysWhyInWords)
{
  // A triangle soup matches few contour points with a small error over them:
  // the reason must be the matches, not "above the threshold".
  RegistrationResult r;
  r.frames.resize(1);
  r.frames[0].contourPoints = 200;
  r.frames[0].matched = 24;
  r.contourErrorPx = 0.4;
  EXPECT_EQ(failureReason(r, MultiStartOptions()),
    "only 12 % of the video contour points matched a model contour (at least 50 % needed)");
  r.frames[0].matched = 190;
  r.contourErrorPx = 7.25;
  r.residualErrorMm = 1.25;
  // The contours first: they are what V13 ranks the starts by.
  EXPECT_EQ(failureReason(r, MultiStartOptions()),
    "the contour error 7.25 px is above the threshold of 4.00 px");
  r.contourErrorPx = 1.0;
  EXPECT_EQ(failureReason(r, MultiStartOptions()),
    "the 3-D residual 1.25 mm is above the threshold of 0.80 mm");
  r.residualErrorMm = 0.3;
  EXPECT_EQ(failureReason(r, MultiStartOptions()), "");

  MultiStartResult outcome;
  outcome.best = r;
  outcome.best.residualErrorMm = 0.95;
  MultiStartOptions o;
  o.failureResidualErrorMm = 0.9;
  outcome.flagFailure(o);
  EXPECT_TRUE(outcome.failure);
  EXPECT_EQ(outcome.failureThresholdPx, 4.0);
  EXPECT_EQ(outcome.failureResidualMm, 0.9);
  EXPECT_EQ(outcome.failureReason, "the 3-D residual 0.95 mm is above the threshold of 0.90 mm");
}

TEST(MultiStartRegistration, RejectsAFailureThresholdOnTheResidualThatIsNotPositive)
{
  MultiStartOptions o;
  for (double bad : { 0.0, -0.5, std::nan("") })
  {
    o.failureResidualErrorMm = bad;
    try
    {
      o.validate();
      FAIL() << "expected an error for " << bad;
    }
    catch (const Error& e)
    {
      EXPECT_STREQ(
        e.what(), "multi-start: the failure threshold on the 3-D residual must be positive");
    }
  }
}
