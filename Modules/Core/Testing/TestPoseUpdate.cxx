#include "RandomGeometry.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/PoseUpdate.h>
#include <vimlop/Core/TaskPool.h>

#include <gtest/gtest.h>

using namespace vimlop;

namespace
{

VideoFrame makeFrame(std::mt19937& rng, int id)
{
  VideoFrame f;
  f.frameId = id;
  f.intrinsics.fx = 300.0 + 10 * id;
  f.intrinsics.fy = 290.0;
  f.intrinsics.cx = 160.0;
  f.intrinsics.cy = 120.0;
  f.intrinsics.widthPx = 320;
  f.intrinsics.heightPx = 240;
  f.cameraToSfm.rotation = fixtures::randomRotation(rng);
  f.cameraToSfm.centre = 5.0 * fixtures::randomUnit(rng);
  return f;
}

/// Point pairs and contour pairs consistent with `truth`, plus noise of `noise`.
PoseUpdateProblem makeProblem(std::mt19937& rng, const SimilarityTransform& truth,
  const std::vector<VideoFrame>& frames, double noise)
{
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PoseUpdateProblem problem;
  problem.frames = &frames;
  problem.kappa = 50.0;
  for (int i = 0; i < 60; ++i)
  {
    const Eigen::Vector3d x = 10.0 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    const Eigen::Matrix3d cov = fixtures::randomCovariance(rng, 0.2, 1.0);
    PointPair p;
    p.data = x;
    p.model = truth.apply(x) + noise * Eigen::Vector3d(n(rng), n(rng), n(rng));
    p.whitening = cov.llt().matrixL().solve(Eigen::Matrix3d::Identity());
    problem.points.push_back(p);
  }
  for (int j = 0; j < static_cast<int>(frames.size()); ++j)
  {
    const CameraPose camera = truth.apply(frames[j].cameraToSfm);
    for (int i = 0; i < 40; ++i)
    {
      const Eigen::Vector3d inCamera(8.0 * u(rng), 6.0 * u(rng), 25.0 + 5.0 * u(rng));
      ContourPair c;
      c.frame = j;
      c.modelPoint = camera.cameraToWorld(inCamera);
      // A normal across the viewing ray, as on an occluding contour.
      const Eigen::Vector3d across = inCamera.cross(fixtures::randomUnit(rng)).normalized();
      c.modelNormal = camera.rotation * across;
      c.videoPixel =
        frames[j].intrinsics.project(inCamera) + noise * Eigen::Vector2d(n(rng), n(rng));
      const Eigen::Vector2d v(
        frames[j].intrinsics.fx * across.x(), frames[j].intrinsics.fy * across.y());
      c.videoNormal = (v.normalized() + 0.1 * noise * Eigen::Vector2d(n(rng), n(rng))).normalized();
      problem.contours.push_back(c);
    }
  }
  return problem;
}

} // namespace

TEST(PoseUpdate, AnalyticJacobianMatchesNumeric)
{
  std::mt19937 rng(7);
  const std::vector<VideoFrame> frames = { makeFrame(rng, 0), makeFrame(rng, 1),
    makeFrame(rng, 2) };
  const SimilarityTransform truth = fixtures::randomSimilarity(rng, 1.0, 20.0, 0.3);
  const PoseUpdateProblem problem = makeProblem(rng, truth, frames, 1.0);
  // Evaluate away from the optimum, where every term has a gradient.
  const SimilarityTransform at = fixtures::randomSimilarity(rng, 0.05, 1.0, 0.02).compose(truth);
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  poseUpdateResiduals(problem, at, r, J);
  ASSERT_EQ(r.size(), 3 * 60 + 4 * 120);
  const double h = 1e-6;
  for (int k = 0; k < 7; ++k)
  {
    Vector7d step = Vector7d::Zero();
    step[k] = h;
    Eigen::VectorXd rPlus, rMinus;
    Eigen::MatrixXd unused;
    poseUpdateResiduals(problem, SimilarityTransform::exp(step).compose(at), rPlus, unused);
    poseUpdateResiduals(problem, SimilarityTransform::exp(-step).compose(at), rMinus, unused);
    const Eigen::VectorXd numeric = (rPlus - rMinus) / (2.0 * h);
    const double scale = std::max(1.0, numeric.cwiseAbs().maxCoeff());
    EXPECT_LT((J.col(k) - numeric).cwiseAbs().maxCoeff() / scale, 1e-6) << "parameter " << k;
  }
  // The cost is half the squared residual norm.
  EXPECT_NEAR(poseUpdateCost(problem, at), 0.5 * r.squaredNorm(), 1e-9 * r.squaredNorm());
}

TEST(PoseUpdate, RecoversTheTransformFromExactPairs)
{
  std::mt19937 rng(8);
  const std::vector<VideoFrame> frames = { makeFrame(rng, 0), makeFrame(rng, 1) };
  const SimilarityTransform truth = fixtures::randomSimilarity(rng, 1.0, 20.0, 0.3);
  const PoseUpdateProblem problem = makeProblem(rng, truth, frames, 0.0);
  const SimilarityTransform start = fixtures::randomSimilarity(rng, 0.05, 2.0, 0.05).compose(truth);
  PoseUpdateOptions options;
  options.maxIterations = 50;
  const PoseUpdateResult result = solvePoseUpdate(problem, start, options);
  EXPECT_LT(result.finalCost, 1e-12);
  EXPECT_NEAR(result.transform.scale, truth.scale, 1e-7);
  EXPECT_LT(rotationAngleBetween(result.transform.rotation, truth.rotation), 1e-8);
  EXPECT_LT((result.transform.translation - truth.translation).norm(), 1e-6);
}

TEST(PoseUpdate, ContoursAloneDetermineThePose)
{
  // Without 3-D pairs the cameras' contour observations still fix T: the
  // 2-D term moves with the cameras, which move with T.
  std::mt19937 rng(9);
  const std::vector<VideoFrame> frames = { makeFrame(rng, 0), makeFrame(rng, 1),
    makeFrame(rng, 2) };
  const SimilarityTransform truth = fixtures::randomSimilarity(rng, 1.0, 20.0, 0.2);
  PoseUpdateProblem problem = makeProblem(rng, truth, frames, 0.0);
  problem.points.clear();
  const SimilarityTransform start = fixtures::randomSimilarity(rng, 0.02, 0.5, 0.01).compose(truth);
  PoseUpdateOptions options;
  options.maxIterations = 100;
  const PoseUpdateResult result = solvePoseUpdate(problem, start, options);
  EXPECT_LT(rotationAngleBetween(result.transform.rotation, truth.rotation), 1e-6);
  EXPECT_LT((result.transform.translation - truth.translation).norm(), 1e-4);
}

TEST(PoseUpdate, ScaleStaysWithinBounds)
{
  std::mt19937 rng(10);
  const std::vector<VideoFrame> frames = { makeFrame(rng, 0) };
  SimilarityTransform truth = fixtures::randomSimilarity(rng, 1.0, 20.0, 0.0);
  truth.scale = 1.5;
  PoseUpdateProblem problem = makeProblem(rng, truth, frames, 0.0);
  problem.minScale = 0.8;
  problem.maxScale = 1.2;
  SimilarityTransform start = truth;
  start.scale = 1.0;
  const PoseUpdateResult result = solvePoseUpdate(problem, start);
  EXPECT_DOUBLE_EQ(result.transform.scale, 1.2);
  EXPECT_TRUE(result.scaleAtBound);
  EXPECT_LT(result.finalCost, result.initialCost);
  // A start outside the bounds is clamped first.
  start.scale = 0.1;
  EXPECT_GE(solvePoseUpdate(problem, start).transform.scale, 0.8);
  problem.minScale = 2.0;
  EXPECT_THROW(solvePoseUpdate(problem, start), Error);
}

TEST(PoseUpdate, ThreadCountDoesNotChangeTheResult)
{
  std::mt19937 rng(11);
  const std::vector<VideoFrame> frames = { makeFrame(rng, 0), makeFrame(rng, 1) };
  const SimilarityTransform truth = fixtures::randomSimilarity(rng, 1.0, 20.0, 0.3);
  PoseUpdateProblem problem = makeProblem(rng, truth, frames, 0.5);
  for (int i = 0; i < 5; ++i)
  {
    problem.points.insert(problem.points.end(), problem.points.begin(), problem.points.end());
  }
  const SimilarityTransform start = fixtures::randomSimilarity(rng, 0.05, 2.0, 0.05).compose(truth);
  TaskPool one(1);
  TaskPool two(2);
  const PoseUpdateResult a = solvePoseUpdate(problem, start, PoseUpdateOptions(), &one);
  const PoseUpdateResult b = solvePoseUpdate(problem, start, PoseUpdateOptions(), &two);
  const PoseUpdateResult c = solvePoseUpdate(problem, start);
  EXPECT_EQ(a.transform.matrix(), b.transform.matrix());
  EXPECT_EQ(a.transform.matrix(), c.transform.matrix());
  EXPECT_EQ(a.finalCost, b.finalCost);
}
