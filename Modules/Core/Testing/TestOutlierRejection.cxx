#include "RandomGeometry.h"
#include <vimlop/Core/ChiSquare.h>
#include <vimlop/Core/Correspondences.h>
#include <vimlop/Core/OutlierRejection.h>

#include <gtest/gtest.h>

using namespace vimlop;

TEST(OutlierRejection, TrimsTheWorstFractionThenTestsTheRest)
{
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 0.3);
  std::vector<Eigen::Vector3d> residuals;
  std::vector<Eigen::Matrix3d> covariances;
  std::vector<double> costs;
  for (int i = 0; i < 100; ++i)
  {
    residuals.emplace_back(n(rng), n(rng), n(rng));
    covariances.push_back(0.09 * Eigen::Matrix3d::Identity());
  }
  // A gross outlier at 5 mm, and a milder one at 2.5 mm.
  residuals[17] = Eigen::Vector3d(5.0, 0.0, 0.0);
  residuals[42] = Eigen::Vector3d(0.0, 2.5, 0.0);
  const Eigen::Matrix3d R = fixtures::randomRotation(rng);
  for (size_t i = 0; i < residuals.size(); ++i)
  {
    residuals[i] = R * residuals[i]; // residuals are in CT; covariances in data axes
    costs.push_back(0.5 * residuals[i].squaredNorm() / 0.09);
  }
  const double threshold = chiSquareQuantile(0.95, 3);
  // Trimming 1 % removes the worst pair only; the chi-square test catches the other.
  const std::vector<char> inliers =
    rejectPointOutliers(residuals, covariances, R, costs, 0.01, threshold);
  EXPECT_EQ(inliers[17], 0);
  EXPECT_EQ(inliers[42], 0);
  int kept = 0;
  for (char c : inliers)
  {
    kept += c;
  }
  // Gaussian inliers mostly pass a 95 % test (with the σ² inflation, nearly all).
  EXPECT_GE(kept, 92);
  // Without trimming and with an infinite threshold nothing is rejected.
  const auto all = rejectPointOutliers(
    residuals, covariances, R, costs, 0.0, std::numeric_limits<double>::infinity());
  EXPECT_EQ(std::count(all.begin(), all.end(), 1), 100);
  // Trimming 10 % removes exactly 10 pairs, the costliest ones.
  const auto trimmed = rejectPointOutliers(
    residuals, covariances, R, costs, 0.1, std::numeric_limits<double>::infinity());
  EXPECT_EQ(std::count(trimmed.begin(), trimmed.end(), 0), 10);
  EXPECT_EQ(trimmed[17], 0);
}

TEST(OutlierRejection, ContourTestsAndPerFrameCap)
{
  ContourMatchOptions options; // Σ2d = 9 px², κ = 200
  std::vector<ContourMatch> matches(10);
  for (int i = 0; i < 10; ++i)
  {
    matches[i].video = i;
    matches[i].model = i;
    matches[i].errorPx = Eigen::Vector2d(1.0, 0.0);
    matches[i].angleRad = 0.02;
  }
  matches[3].errorPx = Eigen::Vector2d(50.0, 0.0); // position outlier (the worst)
  matches[5].angleRad = 0.6;                       // orientation outlier
  matches[8].model = -1;                           // unmatched
  auto inliers = rejectContourOutliers(matches, options, 0.0, 0.0, 0.95, 0.5);
  EXPECT_EQ(inliers, (std::vector<char>{ 1, 1, 1, 0, 1, 0, 1, 1, 0, 1 }));
  // A cap of 10 % of the 9 matched points allows floor(0.9) = 0 outliers:
  // every matched point stays in.
  inliers = rejectContourOutliers(matches, options, 0.0, 0.0, 0.95, 0.1);
  EXPECT_EQ(inliers, (std::vector<char>{ 1, 1, 1, 1, 1, 1, 1, 1, 0, 1 }));
  // A cap of 1 of 9 keeps only the worst one out (the 50 px position error).
  inliers = rejectContourOutliers(matches, options, 0.0, 0.0, 0.95, 0.12);
  EXPECT_EQ(inliers[3], 0);
  EXPECT_EQ(inliers[5], 1);
  // A large mean squared error inflates the test: the 50 px point passes.
  inliers = rejectContourOutliers(matches, options, 900.0, 0.0, 0.95, 0.5);
  EXPECT_EQ(inliers[3], 1);
}

namespace
{

/// Two frames of contour matches with Gaussian errors, σ = 2 px per axis and
/// 0.05 rad, one unmatched point per frame.
std::vector<FrameCorrespondences> gaussianContourMatches(std::mt19937& rng, int perFrame)
{
  std::normal_distribution<double> px(0.0, 2.0);
  std::normal_distribution<double> rad(0.0, 0.05);
  std::vector<FrameCorrespondences> frames(2);
  for (FrameCorrespondences& f : frames)
  {
    for (int i = 0; i < perFrame; ++i)
    {
      ContourMatch m;
      m.video = i;
      m.model = i == 0 ? -1 : i;
      m.errorPx = Eigen::Vector2d(px(rng), px(rng));
      m.angleRad = rad(rng);
      f.matches.push_back(m);
    }
  }
  return frames;
}

} // namespace

TEST(OutlierRejection, ContourSpreadIsTheMeanSquaredErrorOfTheMatchedPoints)
{
  std::vector<FrameCorrespondences> frames(2);
  frames[0].matches.resize(2);
  frames[0].matches[0].model = 0;
  frames[0].matches[0].errorPx = Eigen::Vector2d(3.0, 4.0); // 25 px²
  frames[0].matches[0].angleRad = 0.1;
  frames[0].matches[1].model = -1; // unmatched: not counted
  frames[0].matches[1].errorPx = Eigen::Vector2d(1000.0, 0.0);
  frames[1].matches.resize(1);
  frames[1].matches[0].model = 4;
  frames[1].matches[0].errorPx = Eigen::Vector2d(1.0, 0.0); // 1 px²
  frames[1].matches[0].angleRad = 0.3;
  const ContourErrorSpread mean = contourErrorSpread(frames, false);
  EXPECT_DOUBLE_EQ(mean.squaredDistancePx2, 13.0);
  EXPECT_DOUBLE_EQ(mean.squaredAngleRad2, 0.05);
  const ContourErrorSpread none = contourErrorSpread({}, true);
  EXPECT_EQ(none.squaredDistancePx2, 0.0);
  EXPECT_EQ(none.squaredAngleRad2, 0.0);
}

TEST(OutlierRejection, RobustContourSpreadAgreesWithTheMeanForGaussianErrors)
{
  std::mt19937 rng(5);
  const std::vector<FrameCorrespondences> frames = gaussianContourMatches(rng, 4000);
  const ContourErrorSpread mean = contourErrorSpread(frames, false);
  const ContourErrorSpread robust = contourErrorSpread(frames, true);
  // E|e|² = 2 σ² = 8 px², E θ² = 0.0025 rad²: both estimate them.
  EXPECT_NEAR(mean.squaredDistancePx2, 8.0, 0.4);
  EXPECT_NEAR(robust.squaredDistancePx2, 8.0, 0.4);
  EXPECT_NEAR(mean.squaredAngleRad2, 0.0025, 0.00015);
  EXPECT_NEAR(robust.squaredAngleRad2, 0.0025, 0.00015);
}

TEST(OutlierRejection, ContoursTheModelLacksDoNotWidenTheRobustTest)
{
  std::mt19937 rng(6);
  std::vector<FrameCorrespondences> frames = gaussianContourMatches(rng, 500);
  // 20 % of all points, 40 % of the first frame's: a structure the model
  // lacks, matched 20 px away.
  for (int i = 1; i <= 200; ++i)
  {
    frames[0].matches[static_cast<size_t>(i)].errorPx = Eigen::Vector2d(0.0, 20.0);
  }
  const ContourErrorSpread mean = contourErrorSpread(frames, false);
  const ContourErrorSpread robust = contourErrorSpread(frames, true);
  EXPECT_GT(mean.squaredDistancePx2, 80.0); // 200 x 400 px² over 998 points, and the rest
  EXPECT_LT(robust.squaredDistancePx2, 12.0);
  ContourMatchOptions options;
  options.positionCovariancePx2 = Eigen::Matrix2d::Identity();
  int keptByMean = 0;
  int keptByRobust = 0;
  const std::vector<char> byMean = rejectContourOutliers(
    frames[0].matches, options, mean.squaredDistancePx2, mean.squaredAngleRad2, 0.95, 0.5);
  const std::vector<char> byRobust = rejectContourOutliers(
    frames[0].matches, options, robust.squaredDistancePx2, robust.squaredAngleRad2, 0.95, 0.5);
  for (int i = 1; i <= 200; ++i)
  {
    keptByMean += byMean[static_cast<size_t>(i)];
    keptByRobust += byRobust[static_cast<size_t>(i)];
  }
  EXPECT_EQ(keptByMean, 200); // the mean lets every one of them in
  EXPECT_EQ(keptByRobust, 0); // the median rejects them all
}
