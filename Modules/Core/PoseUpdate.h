#ifndef vimlop_PoseUpdate_h
#define vimlop_PoseUpdate_h

#include <vimlop/Core/SimilarityTransform.h>
#include <vimlop/Core/StableLayout.h>
#include <vimlop/Core/VideoFrame.h>

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace vimlop
{

class TaskPool;

/// @brief A matched 3-D pair: SfM point x and model point y (V2 output).
struct PointPair
{
  Eigen::Vector3d data = Eigen::Vector3d::Zero();  ///< x, SfM frame
  Eigen::Vector3d model = Eigen::Vector3d::Zero(); ///< y, CT frame (mm)
  /// L⁻¹ with Σ = L Lᵀ the point's covariance (mm², SfM axes, V9 scaling included).
  Eigen::Matrix3d whitening = Eigen::Matrix3d::Identity();
};

/// @brief A matched oriented 2-D pair: a model contour sample and a video contour point (V5
/// output).
struct ContourPair
{
  int frame = 0;                                          ///< index into the frames
  Eigen::Vector3d modelPoint = Eigen::Vector3d::Zero();   ///< Y, CT frame (mm)
  Eigen::Vector3d modelNormal = Eigen::Vector3d::UnitZ(); ///< N, unit, CT frame
  Eigen::Vector2d videoPixel = Eigen::Vector2d::Zero();
  Eigen::Vector2d videoNormal = Eigen::Vector2d::UnitX(); ///< unit, pixel axes
};

/**
 * @brief The pose-update problem of one V-IMLOP iteration (V6): with matches
 * fixed, find T = [s, R, t] minimising Σ C3d + Σ C2d.
 *
 * Residuals, each with ½|r|² its term of the cost:
 * - 3-D: r = L⁻¹ (Rᵀ (y - t) - s x), i.e. C3d = ½ dᵀ (R Σ Rᵀ)⁻¹ d with d = y - T(x);
 * - 2-D position: r = Σ2d^(-1/2) (π(Y) - x_p), π the projection through frame
 *   j's camera moved by T (centre T(c_j), rotation R R_cj);
 * - 2-D orientation: r = √κ (n̂_y - n̂_x) with n̂_y the orthographic projection of
 *   N in that camera scaled to pixel axes; ½|r|² = κ (1 - n̂_y · n̂_x).
 * The scale is confined to [minScale, maxScale] (V7).
 */
struct PoseUpdateProblem
{
  std::vector<PointPair> points;
  std::vector<ContourPair> contours;
  /// Cameras of the contour pairs' frames (SfM frame); not owned.
  const std::vector<VideoFrame>* frames = nullptr;
  /// Σ2d^(-1/2) (px⁻¹).
  Matrix2dUnaligned contourWhitening = Matrix2dUnaligned::Identity() / 3.0;
  double kappa = 200.0;
  double minScale = 0.0;
  double maxScale = std::numeric_limits<double>::infinity();
};

/// @brief Options of the Levenberg-Marquardt solver.
struct PoseUpdateOptions
{
  int maxIterations = 20;
  /// Stop when the cost decreases by less than this fraction (default 1e-9).
  double relativeTolerance = 1e-9;
};

/// @brief Outcome of a pose update.
struct PoseUpdateResult
{
  SimilarityTransform transform;
  double initialCost = 0.0;
  double finalCost = 0.0;
  int iterations = 0;
  bool scaleAtBound = false;
};

/// @brief The total cost Σ ½|r|² at `transform`.
double poseUpdateCost(
  const PoseUpdateProblem& problem, const SimilarityTransform& transform, TaskPool* pool = nullptr);

/**
 * @brief All residuals stacked (3-D pairs, then per contour pair position and
 * orientation) and their Jacobian with respect to the left increment δ of
 * T' = exp(δ) ∘ T (see SimilarityTransform::exp) at δ = 0.
 */
void poseUpdateResiduals(const PoseUpdateProblem& problem, const SimilarityTransform& transform,
  Eigen::VectorXd& residuals, Eigen::MatrixXd& jacobian);

/**
 * @brief Minimises the cost by Levenberg-Marquardt on the 7 parameters of the
 * left increment, with analytic Jacobians, starting from `initial` (whose
 * scale is first clamped into the bounds).
 * @param pool optional threads for the sums; the result does not depend on it.
 */
PoseUpdateResult solvePoseUpdate(const PoseUpdateProblem& problem,
  const SimilarityTransform& initial, const PoseUpdateOptions& options = PoseUpdateOptions(),
  TaskPool* pool = nullptr);

} // namespace vimlop

#endif
