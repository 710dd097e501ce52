#include "TestMeshes.h"
#include <vimlop/Core/RegistrationSummary.h>

#include <gtest/gtest.h>

using namespace vimlop;

namespace
{

/// Two points matched on a box cavity [-10, 10]³, the second an outlier, and
/// one frame with three video contour points, two matched, one of them an inlier.
struct Scene
{
  RegistrationModel model{ fixtures::makeBox({ -10, -10, -10 }, { 10, 10, 10 }) };
  RegistrationData data;
  Correspondences matches;
};

Scene makeScene()
{
  Scene s;
  s.data.points = { { 9.0, 0.0, 0.0 }, { 0.0, 7.0, 0.0 } };
  s.data.pointCovariances.assign(2, Eigen::Matrix3d::Identity());
  s.matches.modelPoints = { { 10.0, 0.0, 0.0 }, { 0.0, 10.0, 0.0 } };
  s.matches.residuals = { { 1.0, 0.0, 0.0 }, { 0.0, 3.0, 0.0 } };
  s.matches.costs = { 0.5, 4.5 };
  s.matches.faces = { 0, 1 };
  s.matches.pointInliers = { 1, 0 };
  s.matches.times.match3dMs = 2.0;

  VideoFrame frame;
  frame.frameId = 42;
  frame.contour.resize(3);
  frame.contour[1].pixel = Eigen::Vector2d(10.0, 20.0);
  s.data.frames.push_back(frame);
  FrameCorrespondences f;
  f.visibleSamples.resize(2);
  f.visibleSamples[1].pixel = Eigen::Vector2d(13.0, 24.0);
  f.visibleSamples[1].point = Eigen::Vector3d(1.0, 2.0, 3.0);
  f.matches.resize(3);
  f.matches[0].model = 0;
  f.matches[0].errorPx = Eigen::Vector2d(6.0, 8.0);
  f.matches[0].cost = 100.0;
  f.matches[1].model = 1;
  f.matches[1].errorPx = Eigen::Vector2d(3.0, 4.0);
  f.matches[1].cost = 7.0;
  f.inliers = { 0, 1, 0 };
  s.matches.frames.push_back(f);
  return s;
}

} // namespace

TEST(RegistrationSummary, IterationMetricsCountInliersAndAllMatches)
{
  const Scene s = makeScene();
  IterationRecord record;
  summariseIteration(s.matches, record);
  EXPECT_DOUBLE_EQ(record.cost3d, 0.5);
  EXPECT_EQ(record.pointInliers, 1);
  EXPECT_DOUBLE_EQ(record.residualErrorMm, 1.0);
  EXPECT_EQ(record.contourMatches, 2);
  EXPECT_EQ(record.contourInliers, 1);
  EXPECT_DOUBLE_EQ(record.cost2d, 7.0);
  EXPECT_DOUBLE_EQ(record.contourErrorPx, 7.5); // (10 + 5) / 2
  EXPECT_DOUBLE_EQ(record.cost, 7.5);
  EXPECT_DOUBLE_EQ(record.times.match3dMs, 2.0);
}

TEST(RegistrationSummary, ResultMeasuresResidualsOnTheSurfaceAndContourErrors)
{
  const Scene s = makeScene();
  SimilarityTransform T;
  T.translation = Eigen::Vector3d(-0.5, 0.0, 0.0); // x = 9 moves to 8.5: 1.5 mm from the wall
  const RegistrationResult r = summariseRegistration(s.model, s.data, T, s.matches);
  EXPECT_NEAR(r.residualErrorMm, 1.5, 1e-12);
  EXPECT_EQ(r.pointInliers, s.matches.pointInliers);
  EXPECT_EQ(r.pointMatches, s.matches.modelPoints);
  ASSERT_EQ(r.frames.size(), 1u);
  const FrameResult& f = r.frames[0];
  EXPECT_EQ(f.frameId, 42);
  EXPECT_NEAR(f.cameraToCT.centre.x(), -0.5, 1e-12);
  EXPECT_EQ(f.contourPoints, 3);
  EXPECT_EQ(f.visibleModelSamples, 2);
  EXPECT_EQ(f.matched, 2);
  EXPECT_EQ(f.inliers, 1);
  EXPECT_DOUBLE_EQ(f.contourErrorPx, 7.5);
  EXPECT_DOUBLE_EQ(f.contourErrorInliersPx, 5.0);
  ASSERT_EQ(f.correspondences.size(), 2u);
  EXPECT_EQ(f.correspondences[1].video, 1);
  EXPECT_EQ(f.correspondences[1].videoPixel, Eigen::Vector2d(10.0, 20.0));
  EXPECT_EQ(f.correspondences[1].modelPixel, Eigen::Vector2d(13.0, 24.0));
  EXPECT_TRUE(f.correspondences[1].inlier);
  EXPECT_FALSE(f.correspondences[0].inlier);
  EXPECT_DOUBLE_EQ(r.contourErrorPx, 7.5);
  EXPECT_DOUBLE_EQ(r.contourErrorInliersPx, 5.0);
}
