#include <vimlop/Core/RandomDirection.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>

using namespace vimlop;

TEST(RandomDirection, UnitVectorsSpreadEvenlyOverTheSphere)
{
  std::mt19937_64 rng(7);
  const int n = 20000;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i)
  {
    const Eigen::Vector3d d = randomDirection(rng);
    ASSERT_NEAR(d.norm(), 1.0, 1e-12);
    mean += d / n;
    second += d * d.transpose() / n;
  }
  // Uniform on the sphere: zero mean and E[d d^T] = I / 3 (a bias towards
  // the cube's corners or one axis would show in either).
  EXPECT_LT(mean.norm(), 0.03);
  EXPECT_LT((second - Eigen::Matrix3d::Identity() / 3.0).cwiseAbs().maxCoeff(), 0.015);
}

TEST(RandomDirection, TheSameSeedGivesTheSameDirections)
{
  std::mt19937_64 a(42);
  std::mt19937_64 b(42);
  for (int i = 0; i < 10; ++i)
  {
    EXPECT_EQ(randomDirection(a), randomDirection(b));
  }
}
