#ifndef vimlop_ConvergenceCriteria_h
#define vimlop_ConvergenceCriteria_h

#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/RegistrationResult.h>
#include <vimlop/Core/SimilarityTransform.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

/// @brief Match cost per inlier, comparable between iterations whose inlier
/// counts differ: C3d / n3d + C2d / n2d over the inliers of `record`.
double meanMatchCost(const IterationRecord& record);

/**
 * @brief When the iterations of a stage stop (V11): on convergence, when the
 * change of T is below every threshold, or on a stall, when the mean match
 * cost has stopped falling.
 *
 * Changes of T are measured on the data: the motion of its centroid (mm), and
 * the rotation and scale change times its RMS radius (SfM units), so that the
 * thresholds mean the same whatever the size of the reconstruction. Stalls
 * happen because discrete changes of the match and inlier sets can make the
 * last iterations wander around the solution without settling.
 */
class ConvergenceCriteria
{
public:
  /// @param dataPoints x_i, SfM frame (not empty); `options` must outlive this.
  ConvergenceCriteria(
    const std::vector<Eigen::Vector3d>& dataPoints, const RegistrationOptions& options);

  /// @brief True when from `a` to `b` the centroid moves less than
  /// convergenceTranslationMm, the rotation less than convergenceRotationDeg
  /// and the scale by less than convergenceScaleRelative.
  bool converged(const SimilarityTransform& a, const SimilarityTransform& b) const;

  /**
   * @brief The change from `a` to `b` as displacements in mm: the log-scale
   * and rotation parts of log(b ∘ a⁻¹) times the data radius, and the motion
   * of the data centroid (the step the acceleration compares).
   */
  Vector7d stepInMm(const SimilarityTransform& a, const SimilarityTransform& b) const;

  /// @brief Starts the stall tracking of a stage at `transform`.
  void restartStallTracking(const SimilarityTransform& transform);

  /**
   * @brief Records the mean match cost at `transform`; true when it has not
   * fallen by stallRelativeDecrease below its lowest value for
   * stallIterations iterations in a row.
   */
  bool stalled(double meanCost, const SimilarityTransform& transform);

  /// @brief The estimate with the lowest mean match cost since the restart.
  const SimilarityTransform& bestTransform() const { return this->Best; }

private:
  const RegistrationOptions& Options;
  Eigen::Vector3d Centroid = Eigen::Vector3d::Zero();
  double RadiusMm = 1.0; ///< RMS distance of the data from its centroid (SfM units)
  double BestMeanCost;
  SimilarityTransform Best;
  int IterationsWithoutProgress = 0;
};

} // namespace vimlop

#endif
