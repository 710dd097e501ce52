#ifndef vimlop_RegistrationMetrics_h
#define vimlop_RegistrationMetrics_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/SimilarityTransform.h>

#include <Eigen/Core>

#include <vector>

/**
 * @file RegistrationMetrics.h
 * @brief Error measures of the evaluation protocols (DESIGN section 6).
 */

namespace vimlop
{

/**
 * @brief Target registration error, mm: mean over targets y_k (CT) of
 * |T_est(T_gt⁻¹(y_k)) - y_k|, with both transforms SfM to CT.
 */
double targetRegistrationError(const SimilarityTransform& estimate,
  const SimilarityTransform& truth, const std::vector<Eigen::Vector3d>& targetsCT);

/// @brief Distance between two camera centres, mm.
double cameraPositionError(const CameraPose& estimate, const CameraPose& truth);

/// @brief Angle of R_estᵀ R_truth, degrees.
double cameraAngleErrorDeg(const CameraPose& estimate, const CameraPose& truth);

} // namespace vimlop

#endif
