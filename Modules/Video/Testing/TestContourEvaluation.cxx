#include <vimlop/Core/Error.h>
#include <vimlop/Video/ContourEvaluation.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace vimlop;

namespace
{

/// Truth: a vertical contour at u = 50 from v = 10 to 90, near side left,
/// 10 mm deep. Behind it the wall is at 20 mm for v < 50 (a visible step) and
/// at 10.5 mm below (5 %: no visible step).
void makeTruth(std::vector<ModelContourPoint>& truth, std::vector<double>& depths, DepthMap& depth)
{
  for (int v = 10; v <= 90; ++v)
  {
    ModelContourPoint t;
    t.pixel = Eigen::Vector2d(50.0, v);
    t.pixelNormal = Eigen::Vector2d(1.0, 0.0);
    truth.push_back(t);
    depths.push_back(10.0);
  }
  depth.widthPx = 100;
  depth.heightPx = 100;
  depth.depthMm.assign(100 * 100, 10.0f);
  for (int v = 0; v < 100; ++v)
  {
    for (int u = 51; u < 100; ++u)
    {
      depth.depthMm[v * 100 + u] = v < 50 ? 20.0f : 10.5f;
    }
  }
}

ContourPoint detection(double u, double v, double normalAngleDeg = 0.0)
{
  ContourPoint p;
  p.pixel = Eigen::Vector2d(u, v);
  const double a = normalAngleDeg * M_PI / 180.0;
  p.normal = Eigen::Vector2d(std::cos(a), std::sin(a));
  return p;
}

} // namespace

TEST(ContourEvaluation, CountsPrecisionRecallAndNormalErrors)
{
  std::vector<ModelContourPoint> truth;
  std::vector<double> depths;
  DepthMap depth;
  makeTruth(truth, depths, depth);
  std::vector<ContourPoint> detected;
  for (int v = 10; v < 30; ++v)
  {
    detected.push_back(detection(51.0, v, v < 20 ? 0.0 : 10.0)); // 1 px off: correct
  }
  for (int v = 30; v < 40; ++v)
  {
    detected.push_back(detection(56.0, v)); // 6 px off: wrong
  }
  ContourEvaluation evaluation;
  evaluation.addFrame(detected, truth, depths, depth);
  EXPECT_EQ(evaluation.detectedPoints(), 30);
  EXPECT_EQ(evaluation.correctDetections(), 20);
  EXPECT_DOUBLE_EQ(evaluation.precision(), 20.0 / 30.0);
  // Recall counts v = 10 .. 49 only (a visible step); v = 10 .. 30 lie
  // within 2 px of a detection.
  EXPECT_EQ(evaluation.truthPoints(), 40);
  EXPECT_EQ(evaluation.truthFound(), 21);
  EXPECT_DOUBLE_EQ(evaluation.recall(), 21.0 / 40.0);
  ASSERT_EQ(evaluation.normalErrorsDeg().size(), 20u);
  EXPECT_NEAR(evaluation.medianNormalErrorDeg(), 5.0, 1e-9); // between the 0s and the 10s
  EXPECT_NEAR(evaluation.normalErrorsDeg().front(), 0.0, 1e-9);
  EXPECT_NEAR(evaluation.normalErrorsDeg().back(), 10.0, 1e-9);

  // A second frame pools with the first.
  evaluation.addFrame({}, truth, depths, depth);
  EXPECT_EQ(evaluation.truthPoints(), 80);
  EXPECT_DOUBLE_EQ(evaluation.recall(), 21.0 / 80.0);
}

TEST(ContourEvaluation, ReversedNormalsAreCaught)
{
  std::vector<ModelContourPoint> truth;
  std::vector<double> depths;
  DepthMap depth;
  makeTruth(truth, depths, depth);
  // The normal convention reversed (the intensity gradient instead of its negative).
  ContourEvaluation evaluation;
  evaluation.addFrame({ detection(50.0, 20.0, 180.0) }, truth, depths, depth);
  EXPECT_NEAR(evaluation.medianNormalErrorDeg(), 180.0, 1e-9);
}

TEST(ContourEvaluation, NeedsADepthPerTrueSample)
{
  std::vector<ModelContourPoint> truth(3);
  DepthMap depth;
  ContourEvaluation evaluation;
  EXPECT_THROW(evaluation.addFrame({}, truth, { 1.0 }, depth), Error);
  EXPECT_EQ(ContourEvaluation().precision(), 0.0);
  EXPECT_EQ(ContourEvaluation().recall(), 0.0);
}
