#ifndef vimlop_Rotation_h
#define vimlop_Rotation_h

#include <Eigen/Core>

/**
 * @file Rotation.h
 * @brief Small rotation utilities on 3x3 matrices and rotation vectors.
 *
 * A rotation vector w (radians) stands for the rotation by |w| about w/|w|.
 */

namespace vimlop
{

/// @brief Cross-product matrix: skew(a) * b == a.cross(b).
Eigen::Matrix3d skew(const Eigen::Vector3d& a);

/// @brief Rotation matrix of a rotation vector (Rodrigues' formula, exact near 0).
Eigen::Matrix3d rotationFromVector(const Eigen::Vector3d& rotationVectorRad);

/// @brief Rotation vector of a rotation matrix, angle in [0, pi].
Eigen::Vector3d rotationToVector(const Eigen::Matrix3d& rotation);

/// @brief Angle (radians, in [0, pi]) of the rotation `a^T b`.
double rotationAngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

/// @brief True when `m` is orthonormal with determinant +1 within `tolerance`.
bool isRotation(const Eigen::Matrix3d& m, double tolerance = 1e-6);

/// @brief The rotation closest to `m` in the Frobenius norm (polar decomposition).
Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& m);

/// @brief `from` turned `fraction` of the way to `to` along the shorter
/// geodesic (fraction 0: `from`, 1: `to`), about an axis fixed in space.
Eigen::Matrix3d rotationTowards(
  const Eigen::Matrix3d& from, const Eigen::Matrix3d& to, double fraction);

} // namespace vimlop

#endif
