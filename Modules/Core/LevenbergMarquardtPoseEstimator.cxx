#include <vimlop/Core/LevenbergMarquardtPoseEstimator.h>

#include <vimlop/Core/PoseUpdate.h>

#include <Eigen/Cholesky>

namespace vimlop
{

LevenbergMarquardtPoseEstimator::LevenbergMarquardtPoseEstimator(
  const std::vector<Eigen::Matrix3d>& covariances, const RegistrationOptions& options,
  TaskPool* pool)
  : Options(options)
  , Pool(pool)
{
  this->Whitenings.resize(covariances.size());
  for (size_t i = 0; i < covariances.size(); ++i)
  {
    this->Whitenings[i] = covariances[i].llt().matrixL().solve(Eigen::Matrix3d::Identity());
  }
  this->ContourWhitening =
    options.contourMatch.positionCovariancePx2.llt().matrixL().solve(Eigen::Matrix2d::Identity());
}

SimilarityTransform LevenbergMarquardtPoseEstimator::estimate(const RegistrationData& data,
  const Correspondences& matches, const SimilarityTransform& current) const
{
  PoseUpdateProblem problem;
  problem.frames = &data.frames;
  problem.kappa = this->Options.contourMatch.kappa;
  problem.contourWhitening = this->ContourWhitening;
  problem.minScale = this->Options.minScale;
  problem.maxScale = this->Options.maxScale;
  for (size_t i = 0; i < matches.modelPoints.size(); ++i)
  {
    if (matches.pointInliers[i])
    {
      problem.points.push_back({ data.points[i], matches.modelPoints[i], this->Whitenings[i] });
    }
  }
  for (size_t j = 0; j < matches.frames.size(); ++j)
  {
    const FrameCorrespondences& f = matches.frames[j];
    for (size_t i = 0; i < f.matches.size(); ++i)
    {
      const ContourMatch& m = f.matches[i];
      if (m.model >= 0 && f.inliers[i])
      {
        const ModelContourPoint& y = f.visibleSamples[static_cast<size_t>(m.model)];
        const ContourPoint& x = data.frames[j].contour[i];
        problem.contours.push_back({ static_cast<int>(j), y.point, y.normal, x.pixel, x.normal });
      }
    }
  }
  return solvePoseUpdate(problem, current, this->Options.poseUpdate, this->Pool).transform;
}

} // namespace vimlop
