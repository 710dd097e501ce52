#include "RandomGeometry.h"
#include <vimlop/Core/ChiSquare.h>
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
