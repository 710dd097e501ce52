#include <vimlop/Core/ConvergenceCriteria.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace vimlop;

namespace
{

/// Corners of a cube of half-width 10 about (5, 0, 0): RMS radius 10√3 mm.
std::vector<Eigen::Vector3d> cube()
{
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 8; ++i)
  {
    points.emplace_back(5.0 + (i & 1 ? 10.0 : -10.0), i & 2 ? 10.0 : -10.0, i & 4 ? 10.0 : -10.0);
  }
  return points;
}

} // namespace

TEST(ConvergenceCriteria, ConvergedNeedsEveryChangeBelowItsThreshold)
{
  const RegistrationOptions options; // 0.005 mm, 0.005 degrees, 2e-4
  const ConvergenceCriteria criteria(cube(), options);
  const SimilarityTransform a;
  SimilarityTransform b;
  b.translation = Eigen::Vector3d(0.004, 0.0, 0.0);
  EXPECT_TRUE(criteria.converged(a, b));
  b.translation = Eigen::Vector3d(0.006, 0.0, 0.0);
  EXPECT_FALSE(criteria.converged(a, b));
  b = SimilarityTransform();
  b.rotation = rotationFromVector(Eigen::Vector3d(0.0, 0.0, 0.006 * M_PI / 180.0));
  b.translation = b.rotation * Eigen::Vector3d(-5.0, 0.0, 0.0) + Eigen::Vector3d(5.0, 0.0, 0.0);
  EXPECT_FALSE(criteria.converged(a, b)); // the centroid stays, the rotation is too large
  b = SimilarityTransform();
  b.scale = 1.0003;
  b.translation = (1.0 - b.scale) * Eigen::Vector3d(5.0, 0.0, 0.0);
  EXPECT_FALSE(criteria.converged(a, b));
  b.scale = 1.0001;
  b.translation = (1.0 - b.scale) * Eigen::Vector3d(5.0, 0.0, 0.0);
  EXPECT_TRUE(criteria.converged(a, b));
}

TEST(ConvergenceCriteria, StepInMmMeasuresTheChangeOnTheData)
{
  const RegistrationOptions options;
  const ConvergenceCriteria criteria(cube(), options);
  const double radius = 10.0 * std::sqrt(3.0);
  SimilarityTransform b;
  b.rotation = rotationFromVector(Eigen::Vector3d(0.0, 0.01, 0.0));
  b.translation = Eigen::Vector3d(1.0, 2.0, 3.0);
  const Vector7d step = criteria.stepInMm(SimilarityTransform(), b);
  EXPECT_NEAR(step[0], 0.0, 1e-12);
  EXPECT_NEAR(step[2], radius * 0.01, 1e-9);
  EXPECT_LT(
    (step.tail<3>() - (b.apply(Eigen::Vector3d(5, 0, 0)) - Eigen::Vector3d(5, 0, 0))).norm(),
    1e-12);
}

TEST(ConvergenceCriteria, StallsAfterItsIterationsWithoutProgressAndKeepsTheBest)
{
  RegistrationOptions options;
  options.stallIterations = 3;
  options.stallRelativeDecrease = 0.01;
  ConvergenceCriteria criteria(cube(), options);
  SimilarityTransform T;
  criteria.restartStallTracking(T);
  auto at = [](double x)
  {
    SimilarityTransform t;
    t.translation.x() = x;
    return t;
  };
  EXPECT_FALSE(criteria.stalled(10.0, at(1.0)));
  EXPECT_FALSE(criteria.stalled(9.0, at(2.0)));
  EXPECT_FALSE(criteria.stalled(8.95, at(3.0))); // less than 1 % lower: no progress
  EXPECT_FALSE(criteria.stalled(12.0, at(4.0)));
  EXPECT_TRUE(criteria.stalled(9.0, at(5.0)));
  EXPECT_EQ(criteria.bestTransform().translation.x(), 2.0);
  // A restart forgets the lowest cost.
  criteria.restartStallTracking(at(7.0));
  EXPECT_EQ(criteria.bestTransform().translation.x(), 7.0);
  EXPECT_FALSE(criteria.stalled(100.0, at(8.0)));
  EXPECT_EQ(criteria.bestTransform().translation.x(), 8.0);
}

TEST(ConvergenceCriteria, MeanMatchCostIsPerInlier)
{
  IterationRecord record;
  record.cost3d = 30.0;
  record.pointInliers = 10;
  record.cost2d = 8.0;
  record.contourInliers = 4;
  EXPECT_DOUBLE_EQ(meanMatchCost(record), 5.0);
  record.contourInliers = 0;
  record.cost2d = 0.0;
  EXPECT_DOUBLE_EQ(meanMatchCost(record), 3.0);
}

TEST(ConvergenceCriteria, AnEmptyPointSetGetsAClearError)
{
  const RegistrationOptions options;
  try
  {
    ConvergenceCriteria criteria({}, options);
    ADD_FAILURE() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_EQ(std::string(e.what()), "convergence criteria: the point set is empty");
  }
}
