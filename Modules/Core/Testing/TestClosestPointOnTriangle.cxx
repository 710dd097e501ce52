#include <vimlop/Core/ClosestPointOnTriangle.h>

#include <gtest/gtest.h>

#include <random>

using namespace vimlop;

namespace
{

/// Closest point by dense sampling of the barycentric simplex (the reference).
double sampledDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
  const Eigen::Vector3d& c, int n = 300)
{
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i)
  {
    for (int j = 0; i + j <= n; ++j)
    {
      const double u = double(i) / n;
      const double v = double(j) / n;
      best = std::min(best, (a + u * (b - a) + v * (c - a) - p).norm());
    }
  }
  return best;
}

} // namespace

TEST(ClosestPointOnTriangle, AgreesWithDenseSampling)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  for (int trial = 0; trial < 200; ++trial)
  {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng));
    const Eigen::Vector3d b(u(rng), u(rng), u(rng));
    const Eigen::Vector3d c(u(rng), u(rng), u(rng));
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    Eigen::Vector3d w;
    const Eigen::Vector3d q = closestPointOnTriangle(p, a, b, c, &w);
    EXPECT_NEAR(w.sum(), 1.0, 1e-12);
    EXPECT_GE(w.minCoeff(), -1e-12);
    EXPECT_LT((w[0] * a + w[1] * b + w[2] * c - q).norm(), 1e-12);
    const double d = (q - p).norm();
    // Never worse than any sample, and the sampling grid is fine enough to be close.
    EXPECT_LE(d, sampledDistance(p, a, b, c) + 1e-12);
    EXPECT_GT(d, sampledDistance(p, a, b, c) - 0.05);
  }
}

TEST(ClosestPointOnTriangle, InteriorProjectionAndRegions)
{
  const Eigen::Vector3d a(0, 0, 0), b(4, 0, 0), c(0, 4, 0);
  // Above the interior: straight down.
  EXPECT_LT(
    (closestPointOnTriangle({ 1, 1, 3 }, a, b, c) - Eigen::Vector3d(1, 1, 0)).norm(), 1e-15);
  // Beyond corner b.
  EXPECT_LT((closestPointOnTriangle({ 6, -1, 1 }, a, b, c) - b).norm(), 1e-15);
  // Beside edge bc.
  EXPECT_LT(
    (closestPointOnTriangle({ 3, 3, 0 }, a, b, c) - Eigen::Vector3d(2, 2, 0)).norm(), 1e-12);
}

TEST(ClosestPointOnTriangle, DegenerateTriangles)
{
  // Collinear corners: the closest point of the segment [0, 2] on x.
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(2, 0, 0);
  Eigen::Vector3d w;
  const Eigen::Vector3d q = closestPointOnTriangle({ 1.5, 1, 0 }, a, b, c, &w);
  EXPECT_LT((q - Eigen::Vector3d(1.5, 0, 0)).norm(), 1e-12);
  EXPECT_NEAR(w.sum(), 1.0, 1e-12);
  // All corners coincide.
  const Eigen::Vector3d r = closestPointOnTriangle({ 3, 4, 0 }, a, a, a, &w);
  EXPECT_LT(r.norm(), 1e-15);
  EXPECT_TRUE(w.allFinite());
}
