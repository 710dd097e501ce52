#include <vimlop/Core/ContourMatcher.h>

#include <gtest/gtest.h>

#include <random>

using namespace vimlop;

namespace
{

Eigen::Vector2d unit(double angle)
{
  return { std::cos(angle), std::sin(angle) };
}

} // namespace

TEST(ContourMatcher, TreeSearchMatchesBruteForce)
{
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> where(0.0, 300.0);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::vector<ModelContourPoint> model(1500);
  std::vector<Eigen::Vector2d> pixels;
  for (ModelContourPoint& m : model)
  {
    m.pixel = { where(rng), where(rng) };
    m.pixelNormal = unit(angle(rng));
    pixels.push_back(m.pixel);
  }
  std::vector<ContourPoint> video(400);
  for (ContourPoint& v : video)
  {
    v.pixel = { where(rng), where(rng) };
    v.normal = unit(angle(rng));
  }
  ContourMatchOptions options;
  options.positionCovariancePx2 << 9.0, 2.0, 2.0, 4.0; // anisotropic
  options.kappa = 20.0;
  const KdTree2D tree(pixels);
  const auto fast = matchContours(video, model, tree, options);
  const auto reference = matchContoursBruteForce(video, model, options);
  ASSERT_EQ(fast.size(), reference.size());
  for (size_t i = 0; i < fast.size(); ++i)
  {
    EXPECT_EQ(fast[i].model, reference[i].model) << i;
    EXPECT_NEAR(fast[i].cost, reference[i].cost, 1e-9);
    if (fast[i].model >= 0)
    {
      EXPECT_LE(fast[i].angleRad, options.maxAngleDeg * M_PI / 180.0 + 1e-12);
    }
  }
}

TEST(ContourMatcher, OrientationDecidesBetweenNearbyCandidates)
{
  // Two model samples at equal distance: one with the right normal, one flipped.
  std::vector<ModelContourPoint> model(2);
  model[0].pixel = { 10.0, 0.0 };
  model[0].pixelNormal = unit(M_PI);
  model[1].pixel = { -10.0, 0.0 };
  model[1].pixelNormal = unit(0.0);
  const std::vector<ContourPoint> video = { { { 0.0, 0.0 }, unit(0.1) } };
  const KdTree2D tree({ model[0].pixel, model[1].pixel });
  ContourMatchOptions options;
  options.positionCovariancePx2 = 9.0 * Eigen::Matrix2d::Identity();
  const auto matches = matchContours(video, model, tree, options);
  ASSERT_EQ(matches[0].model, 1);
  EXPECT_NEAR(matches[0].angleRad, 0.1, 1e-12);
  EXPECT_NEAR(matches[0].cost, 0.5 * 100.0 / 9.0 + 200.0 * (1.0 - std::cos(0.1)), 1e-9);
  EXPECT_EQ(matches[0].errorPx, Eigen::Vector2d(-10.0, 0.0));
  // With only the flipped sample, the angle bound leaves the point unmatched.
  const KdTree2D onlyFlipped({ model[0].pixel });
  const std::vector<ModelContourPoint> flipped = { model[0] };
  EXPECT_EQ(matchContours(video, flipped, onlyFlipped, options)[0].model, -1);
}
