#include "RandomGeometry.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/SimilarityEstimation.h>

#include <gtest/gtest.h>

using namespace vimlop;

TEST(SimilarityEstimation, RecoversAKnownSimilarity)
{
  std::mt19937 rng(5);
  const SimilarityTransform truth = fixtures::randomSimilarity(rng, 3.0, 50.0, 0.5);
  std::vector<Eigen::Vector3d> source, target;
  std::uniform_real_distribution<double> u(-20.0, 20.0);
  for (int i = 0; i < 30; ++i)
  {
    source.emplace_back(u(rng), u(rng), u(rng));
    target.push_back(truth.apply(source.back()));
  }
  const SimilarityTransform t = estimateSimilarity(source, target);
  EXPECT_NEAR(t.scale, truth.scale, 1e-10);
  EXPECT_LT((t.matrix() - truth.matrix()).norm(), 1e-9);
  // Clamped scale: the rotation stays, the translation follows.
  const SimilarityTransform clamped = estimateSimilarity(source, target, 0.1, 0.5 * truth.scale);
  EXPECT_DOUBLE_EQ(clamped.scale, 0.5 * truth.scale);
  EXPECT_LT(rotationAngleBetween(clamped.rotation, truth.rotation), 1e-9);
  EXPECT_THROW(estimateSimilarity({ source[0], source[1] }, { target[0], target[1] }), Error);
  EXPECT_THROW(estimateSimilarity(std::vector<Eigen::Vector3d>(5, source[0]), target), Error);
}
