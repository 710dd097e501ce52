#include "TestMeshes.h"
#include <vimlop/Core/CorrespondenceSearch.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Core/TaskPool.h>
#include <vimlop/Core/VisibleModelContours.h>

#include <gtest/gtest.h>

using namespace vimlop;

namespace
{

const RegistrationModel& cavityModel()
{
  static const RegistrationModel model(fixtures::makeCavityWithBlobs());
  return model;
}

const SyntheticTrial& trial()
{
  static const SyntheticTrial t = []
  {
    SyntheticOptions o;
    o.points = 400;
    return makeSyntheticTrial(cavityModel(), o, 11);
  }();
  return t;
}

RegistrationOptions optionsFor(RegistrationMethod method)
{
  RegistrationOptions o;
  o.method = method;
  return o;
}

} // namespace

TEST(CorrespondenceSearch, MatchesEveryPointAndFrameAtTheTruth)
{
  const RegistrationOptions options = optionsFor(RegistrationMethod::VIMLOP);
  TaskPool pool(2);
  CorrespondenceSearch search(cavityModel(), trial().data, options, pool);
  const SimilarityTransform& T = trial().truthSfmToCT;
  const Correspondences c = search.find(T, true, false);

  const size_t n = trial().data.points.size();
  ASSERT_EQ(c.modelPoints.size(), n);
  ASSERT_EQ(c.pointInliers.size(), n);
  int inliers = 0;
  for (size_t i = 0; i < n; ++i)
  {
    EXPECT_LT(
      (c.residuals[i] - (c.modelPoints[i] - T.apply(trial().data.points[i]))).norm(), 1e-12);
    EXPECT_GE(c.faces[i], 0);
    // Noise of 0.5 mm at most a few sigma from the surface.
    EXPECT_LT(c.residuals[i].norm(), 3.0);
    inliers += c.pointInliers[i];
  }
  // At the truth nearly every point passes the 95 % chi-square test.
  EXPECT_GT(inliers, 0.85 * n);
  ASSERT_EQ(c.frames.size(), trial().data.frames.size());
  for (size_t j = 0; j < c.frames.size(); ++j)
  {
    const FrameCorrespondences& f = c.frames[j];
    EXPECT_EQ(f.matches.size(), trial().data.frames[j].contour.size());
    EXPECT_EQ(f.inliers.size(), f.matches.size());
    EXPECT_FALSE(f.visibleSamples.empty());
    int matched = 0;
    for (const ContourMatch& m : f.matches)
    {
      matched += m.model >= 0;
      if (m.model >= 0)
      {
        EXPECT_LT(m.model, static_cast<int>(f.visibleSamples.size()));
      }
    }
    EXPECT_GT(matched, 0.8 * f.matches.size());
  }
}

TEST(CorrespondenceSearch, WithoutContoursTheFramesStayEmpty)
{
  const RegistrationOptions options = optionsFor(RegistrationMethod::VIMLOP);
  TaskPool pool(1);
  CorrespondenceSearch search(cavityModel(), trial().data, options, pool);
  const Correspondences c = search.find(trial().truthSfmToCT, false, false);
  ASSERT_EQ(c.frames.size(), trial().data.frames.size());
  for (const FrameCorrespondences& f : c.frames)
  {
    EXPECT_TRUE(f.visibleSamples.empty());
    EXPECT_TRUE(f.matches.empty());
  }
  EXPECT_EQ(c.times.contoursMs, 0.0);
}

TEST(CorrespondenceSearch, TrimmingRejectsAtLeastTheTrimFraction)
{
  const RegistrationOptions options = optionsFor(RegistrationMethod::IMLP);
  TaskPool pool(1);
  CorrespondenceSearch search(cavityModel(), trial().data, options, pool);
  const Correspondences c = search.find(trial().truthSfmToCT, false, true);
  int outliers = 0;
  for (char in : c.pointInliers)
  {
    outliers += !in;
  }
  EXPECT_GE(outliers, static_cast<int>(options.trimFraction * c.pointInliers.size()));
}

TEST(CorrespondenceSearch, TrimmedICPMatchesClosestPointsWithoutChiSquare)
{
  RegistrationOptions options = optionsFor(RegistrationMethod::TrimmedICP);
  TaskPool pool(1);
  CorrespondenceSearch search(cavityModel(), trial().data, options, pool);
  const SimilarityTransform& T = trial().truthSfmToCT;
  const Correspondences c = search.find(T, false, false);
  for (size_t i = 0; i < c.modelPoints.size(); ++i)
  {
    const Eigen::Vector3d z = T.apply(trial().data.points[i]);
    const SurfacePoint p = cavityModel().tree().closestPoint(z);
    EXPECT_LT((c.modelPoints[i] - p.point).norm(), 1e-9);
    EXPECT_NEAR(c.costs[i], 0.5 * (p.point - z).squaredNorm(), 1e-9);
    // No chi-square test and no trimming: every pair is an inlier.
    EXPECT_TRUE(c.pointInliers[i]);
  }
}

TEST(CorrespondenceSearch, EqualInfluenceScalesTheCovariancesOfContourMethodsOnly)
{
  const RegistrationData& data = trial().data;
  TaskPool pool(1);
  const RegistrationOptions vimlop = optionsFor(RegistrationMethod::VIMLOP);
  const CorrespondenceSearch withContours(cavityModel(), data, vimlop, pool);
  const double factor =
    data.points.size() * (1.0 - vimlop.trimFraction) / data.numberOfContourPoints();
  EXPECT_LT((withContours.covariances()[5] - factor * data.pointCovariances[5]).norm(),
    1e-12 * data.pointCovariances[5].norm() * factor);
  const CorrespondenceSearch pointsOnly(
    cavityModel(), data, optionsFor(RegistrationMethod::IMLP), pool);
  EXPECT_EQ(pointsOnly.covariances()[5], data.pointCovariances[5]);
}

// V4 in the loop: the model contours a video contour may match are the ones
// the camera sees. Video contour points are put exactly where the outline of
// a far blob is hidden behind a near one: were hidden samples candidates,
// each would match one at zero distance with the same normal.
TEST(CorrespondenceSearch, VideoContoursMatchOnlyModelContoursTheCameraSees)
{
  const RegistrationModel model(fixtures::twoBlobs());
  const PinholeCamera k = fixtures::twoBlobsCamera();
  const CameraPose camera; // at the origin, looking along +z
  const std::vector<ModelContourPoint> all = extractOccludingContours(model.mesh(), k, camera);
  const std::vector<ModelContourPoint> seen = visibleModelContours(model, k, camera);

  RegistrationData data;
  VideoFrame frame;
  frame.intrinsics = k;
  frame.cameraToSfm = camera;
  // Both lists are in extraction order: the samples missing from `seen` are the hidden ones.
  size_t next = 0;
  for (const ModelContourPoint& s : all)
  {
    if (next < seen.size() && seen[next].point == s.point)
    {
      ++next;
      continue;
    }
    frame.contour.push_back({ s.pixel, s.pixelNormal });
  }
  ASSERT_EQ(next, seen.size());
  ASSERT_GE(frame.contour.size(), 20u);
  data.frames.push_back(frame);
  for (int i = 0; i < 10; ++i)
  {
    data.points.push_back(model.mesh().vertices()[static_cast<size_t>(7 * i)]);
    data.pointCovariances.push_back(0.09 * Eigen::Matrix3d::Identity());
  }

  const RegistrationOptions options = optionsFor(RegistrationMethod::VIMLOP);
  TaskPool pool(1);
  CorrespondenceSearch search(model, data, options, pool);
  const Correspondences c = search.find(SimilarityTransform(), true, false);
  const FrameCorrespondences& f = c.frames.at(0);
  EXPECT_EQ(f.visibleSamples.size(), seen.size());
  int atTheirOwnPixel = 0;
  for (const ContourMatch& m : f.matches)
  {
    if (m.model >= 0)
    {
      atTheirOwnPixel += m.errorPx.norm() < 0.5;
    }
  }
  // Only where the hidden arc meets the near outline can a visible sample lie that close.
  EXPECT_LE(atTheirOwnPixel, 2);
}
