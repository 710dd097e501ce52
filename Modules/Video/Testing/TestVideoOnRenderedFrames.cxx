// Contours and structure from motion on pictures of the virtual endoscope
// (Rendering module), against the simulation's ground truth.

#include "RenderedSequence.h"
#include <vimlop/Core/OccludingContours.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/SimilarityEstimation.h>
#include <vimlop/Video/ContourEvaluation.h>
#include <vimlop/Video/OccludingContourDetector.h>
#include <vimlop/Video/StructureFromMotion.h>

#include <gtest/gtest.h>

using namespace vimlop;

TEST(VideoOnRenderedFrames, ContourDetectorFindsTheTrueOccludingContours)
{
  const fixtures::Sequence& s = fixtures::sequence();
  ContourDetectionOptions options;
  options.spacingPx = 0.0;
  const OccludingContourDetector detector(options);
  ContourEvaluation evaluation;
  for (size_t f = 0; f < s.frames.size(); ++f)
  {
    const std::vector<ModelContourPoint> samples =
      extractOccludingContours(s.mesh, s.intrinsics, s.poses[f]);
    std::vector<Eigen::Vector3d> points;
    for (const ModelContourPoint& m : samples)
    {
      points.push_back(m.point);
    }
    std::vector<char> visible;
    s.model->visibility().classify(s.intrinsics, s.poses[f], points, visible);
    std::vector<ModelContourPoint> truth;
    std::vector<double> depths;
    for (size_t i = 0; i < samples.size(); ++i)
    {
      if (visible[i])
      {
        truth.push_back(samples[i]);
        depths.push_back(s.poses[f].worldToCamera(samples[i].point).z());
      }
    }
    evaluation.addFrame(detector.detect(s.frames[f]), truth, depths, s.depth[f]);
  }
  ASSERT_GT(evaluation.truthPoints(), 1000);
  EXPECT_GE(evaluation.precision(), 0.8);
  EXPECT_GE(evaluation.recall(), 0.8);
  EXPECT_LE(evaluation.medianNormalErrorDeg(), 15.0);
  std::printf("contours on the tube: precision %.3f, recall %.3f, median normal error %.1f deg\n",
    evaluation.precision(), evaluation.recall(), evaluation.medianNormalErrorDeg());
}

TEST(VideoOnRenderedFrames, StructureFromMotionRecoversTheCamerasAndTheSurface)
{
  const fixtures::Sequence& s = fixtures::sequence();
  const SfmReconstruction sfm = StructureFromMotion().reconstruct(s.frames, s.intrinsics, s.names);
  ASSERT_EQ(sfm.numberOfRegisteredFrames(), static_cast<int>(s.frames.size()));
  EXPECT_GT(sfm.points.size(), 200u);
  EXPECT_LT(sfm.rmsReprojectionErrorPx(), 1.0);
  EXPECT_EQ(sfm.frames[3].name, "frame03.png");
  // Up to a similarity, the cameras are the true ones.
  std::vector<Eigen::Vector3d> estimated;
  std::vector<Eigen::Vector3d> truth;
  for (size_t f = 0; f < s.poses.size(); ++f)
  {
    estimated.push_back(sfm.frames[f].cameraToSfm.centre);
    truth.push_back(s.poses[f].centre);
  }
  const SimilarityTransform t = estimateSimilarity(estimated, truth);
  // One SfM unit is the mean step between frames (0.5 mm here, plus sway).
  EXPECT_NEAR(t.scale, 0.5, 0.1);
  double pathLength = 0.0;
  for (size_t f = 1; f < truth.size(); ++f)
  {
    pathLength += (truth[f] - truth[f - 1]).norm();
  }
  for (size_t f = 0; f < s.poses.size(); ++f)
  {
    EXPECT_LT((t.apply(estimated[f]) - truth[f]).norm(), 0.01 * pathLength) << f;
    const CameraPose moved = t.apply(sfm.frames[f].cameraToSfm);
    EXPECT_LT(rotationAngleBetween(moved.rotation, s.poses[f].rotation) * 180.0 / M_PI, 0.5) << f;
  }
  // The points lie on the tube's surface.
  std::vector<double> distances;
  for (const SfmReconstruction::Point& p : sfm.points)
  {
    distances.push_back(s.model->locator().closestPoint(t.apply(p.position)).distanceMm);
  }
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
  EXPECT_LT(distances[distances.size() / 2], 0.1);
}

TEST(VideoOnRenderedFrames, StructureFromMotionIsTheSameOnOneThreadAsOnTwo)
{
  const fixtures::Sequence& s = fixtures::sequence();
  StructureFromMotionOptions one;
  one.threads = 1;
  StructureFromMotionOptions two;
  two.threads = 2;
  const SfmReconstruction a = StructureFromMotion(one).reconstruct(s.frames, s.intrinsics, s.names);
  const SfmReconstruction b = StructureFromMotion(two).reconstruct(s.frames, s.intrinsics, s.names);
  ASSERT_GT(a.points.size(), 200u);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t p = 0; p < a.points.size(); ++p)
  {
    EXPECT_EQ(a.points[p].position, b.points[p].position) << p;
    EXPECT_EQ(a.points[p].covariance, b.points[p].covariance) << p;
    EXPECT_EQ(a.points[p].observations.size(), b.points[p].observations.size()) << p;
  }
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (size_t f = 0; f < a.frames.size(); ++f)
  {
    EXPECT_EQ(a.frames[f].registered, b.frames[f].registered) << f;
    EXPECT_EQ(a.frames[f].cameraToSfm.centre, b.frames[f].cameraToSfm.centre) << f;
    EXPECT_EQ(a.frames[f].cameraToSfm.rotation, b.frames[f].cameraToSfm.rotation) << f;
  }
}
