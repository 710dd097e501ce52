#include "RandomGeometry.h"
#include <vimlop/Core/ClosedFormSimilarityEstimator.h>
#include <vimlop/Core/LevenbergMarquardtPoseEstimator.h>
#include <vimlop/Core/Rotation.h>

#include <gtest/gtest.h>

#include <random>

using namespace vimlop;

namespace
{

/// Exact pairs: data x_i and model points T(x_i), every pair an inlier.
struct ExactPairs
{
  RegistrationData data;
  Correspondences matches;
  SimilarityTransform truth;
};

ExactPairs makePairs(int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> where(-10.0, 10.0);
  ExactPairs p;
  p.truth.scale = 1.2;
  p.truth.rotation = rotationFromVector(Eigen::Vector3d(0.1, -0.05, 0.08));
  p.truth.translation = Eigen::Vector3d(2.0, -1.0, 3.0);
  for (int i = 0; i < n; ++i)
  {
    const Eigen::Vector3d x(where(rng), where(rng), where(rng));
    p.data.points.push_back(x);
    p.data.pointCovariances.push_back(fixtures::randomCovariance(rng, 0.3, 0.6));
    p.matches.modelPoints.push_back(p.truth.apply(x));
    p.matches.pointInliers.push_back(1);
  }
  return p;
}

void expectRecovers(const PoseEstimator& estimator, const ExactPairs& p, double toleranceMm)
{
  const SimilarityTransform estimate = estimator.estimate(p.data, p.matches, SimilarityTransform());
  EXPECT_NEAR(estimate.scale, p.truth.scale, 1e-6);
  EXPECT_LT(rotationAngleBetween(estimate.rotation, p.truth.rotation), 1e-6);
  EXPECT_LT((estimate.translation - p.truth.translation).norm(), toleranceMm);
}

} // namespace

TEST(PoseEstimator, BothEstimatorsRecoverTheTransformOfExactPairs)
{
  const ExactPairs p = makePairs(50, 3);
  RegistrationOptions options;
  options.poseUpdate.maxIterations = 50;
  const LevenbergMarquardtPoseEstimator lm(p.data.pointCovariances, options);
  const ClosedFormSimilarityEstimator closedForm;
  expectRecovers(lm, p, 1e-5);
  expectRecovers(closedForm, p, 1e-9);
}

TEST(PoseEstimator, OutliersAreLeftOut)
{
  ExactPairs p = makePairs(50, 4);
  for (int i = 0; i < 10; ++i)
  {
    p.matches.modelPoints[i] += Eigen::Vector3d(30.0, -20.0, 15.0);
    p.matches.pointInliers[i] = 0;
  }
  RegistrationOptions options;
  options.poseUpdate.maxIterations = 50;
  expectRecovers(LevenbergMarquardtPoseEstimator(p.data.pointCovariances, options), p, 1e-5);
  expectRecovers(ClosedFormSimilarityEstimator(), p, 1e-9);
}

TEST(PoseEstimator, BothKeepTheScaleWithinItsBounds)
{
  const ExactPairs p = makePairs(50, 5);
  RegistrationOptions options;
  options.minScale = 0.9;
  options.maxScale = 1.1;
  const LevenbergMarquardtPoseEstimator lm(p.data.pointCovariances, options);
  const ClosedFormSimilarityEstimator closedForm(options.minScale, options.maxScale);
  for (const PoseEstimator* estimator :
    { static_cast<const PoseEstimator*>(&lm), static_cast<const PoseEstimator*>(&closedForm) })
  {
    const SimilarityTransform T = estimator->estimate(p.data, p.matches, SimilarityTransform());
    EXPECT_NEAR(T.scale, 1.1, 1e-12);
  }
}

TEST(PoseEstimator, ClosedFormKeepsTheEstimateWithFewerThanThreeInliers)
{
  ExactPairs p = makePairs(10, 6);
  for (size_t i = 2; i < p.matches.pointInliers.size(); ++i)
  {
    p.matches.pointInliers[i] = 0;
  }
  SimilarityTransform current;
  current.translation = Eigen::Vector3d(1.0, 2.0, 3.0);
  const SimilarityTransform T =
    ClosedFormSimilarityEstimator().estimate(p.data, p.matches, current);
  EXPECT_EQ(T.translation, current.translation);
}
