#ifndef vimlop_LevenbergMarquardtPoseEstimator_h
#define vimlop_LevenbergMarquardtPoseEstimator_h

#include <vimlop/Core/PoseEstimator.h>
#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/StableLayout.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

class TaskPool;

/**
 * @brief The pose update of V-IMLOP and IMLP (V6, V7): builds the
 * PoseUpdateProblem of the inlier 3-D pairs and inlier contour pairs and
 * solves it with solvePoseUpdate(), starting from the current estimate.
 */
class LevenbergMarquardtPoseEstimator : public PoseEstimator
{
public:
  /**
   * @param covariances Σ_i per data point as matched (mm², SfM axes, with the
   *   V9 scaling, see CorrespondenceSearch::covariances())
   * @param options Σ2d and κ (contourMatch), the scale bounds and the solver
   *   options (poseUpdate) are used; must outlive the estimator
   * @param pool optional threads for the solver's sums; not owned
   */
  LevenbergMarquardtPoseEstimator(const std::vector<Eigen::Matrix3d>& covariances,
    const RegistrationOptions& options, TaskPool* pool = nullptr);

  SimilarityTransform estimate(const RegistrationData& data, const Correspondences& matches,
    const SimilarityTransform& current) const override;

private:
  const RegistrationOptions& Options;
  TaskPool* Pool;
  std::vector<Eigen::Matrix3d> Whitenings; ///< L⁻¹ of Σ_i = L Lᵀ
  Matrix2dUnaligned ContourWhitening;      ///< Σ2d^(-1/2), px⁻¹
};

} // namespace vimlop

#endif
