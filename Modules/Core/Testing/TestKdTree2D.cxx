#include <vimlop/Core/KdTree2D.h>

#include <gtest/gtest.h>

#include <random>

using namespace vimlop;

TEST(KdTree2D, NearestMatchesBruteForce)
{
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 640.0);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 2000; ++i)
  {
    points.emplace_back(u(rng), u(rng));
  }
  const KdTree2D tree(points);
  for (int q = 0; q < 500; ++q)
  {
    const Eigen::Vector2d query(u(rng), u(rng));
    int best = -1;
    double bestD2 = std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(points.size()); ++i)
    {
      if ((points[i] - query).squaredNorm() < bestD2)
      {
        bestD2 = (points[i] - query).squaredNorm();
        best = i;
      }
    }
    EXPECT_EQ(tree.nearest(query), best);
  }
}

TEST(KdTree2D, VisitReachesEveryPointWithinTheRadius)
{
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 30; ++i)
  {
    for (int j = 0; j < 30; ++j)
    {
      points.emplace_back(i, j);
    }
  }
  const KdTree2D tree(points);
  double radius2 = 4.0;
  int within = 0;
  tree.visit({ 10.2, 10.7 }, radius2,
    [&](int i) { within += (points[i] - Eigen::Vector2d(10.2, 10.7)).squaredNorm() <= 4.0; });
  // Lattice points within 2 of (10.2, 10.7).
  int expected = 0;
  for (const auto& p : points)
  {
    expected += (p - Eigen::Vector2d(10.2, 10.7)).squaredNorm() <= 4.0;
  }
  EXPECT_EQ(within, expected);
  EXPECT_EQ(KdTree2D().nearest({ 0, 0 }), -1);
}
