#ifndef vimlop_SimilarityTransform_h
#define vimlop_SimilarityTransform_h

#include <vimlop/Core/CameraPose.h>

#include <Eigen/Core>

namespace vimlop
{

/// @brief 7-vector (log-scale, rotation vector in radians, translation in mm).
using Vector7d = Eigen::Matrix<double, 7, 1>;

/**
 * @brief Similarity transform T(x) = s R x + t.
 *
 * In a registration it maps the SfM frame to the CT frame: `scale` is
 * dimensionless (SfM units to mm), `rotation` is a proper rotation and
 * `translation` is in mm. A camera pose in the SfM frame maps to the CT frame
 * with centre T(c) and rotation R R_c (see apply(const CameraPose&)).
 */
struct SimilarityTransform
{
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  /// @brief T(x) = s R x + t.
  Eigen::Vector3d apply(const Eigen::Vector3d& point) const
  {
    return scale * (rotation * point) + translation;
  }

  /// @brief Moves a camera: centre T(c), rotation R R_c (scale does not act on directions).
  CameraPose apply(const CameraPose& pose) const;

  /// @brief This transform after `first`: x -> this(first(x)).
  SimilarityTransform compose(const SimilarityTransform& first) const;

  /// @brief The inverse transform: x -> R^T (x - t) / s.
  SimilarityTransform inverse() const;

  /// @brief Homogeneous 4x4 matrix [sR t; 0 1].
  Eigen::Matrix4d matrix() const;

  /**
   * @brief Transform from a homogeneous 4x4 matrix [sR t; 0 1].
   * @throws vimlop::Error if the matrix is not a similarity with positive scale.
   */
  static SimilarityTransform fromMatrix(const Eigen::Matrix4d& m, double toleranceRotation = 1e-6);

  /**
   * @brief Transform from the 7-vector v = (log s, w, t).
   *
   * This is the chart scale x SO(3) x R^3 used by the pose update: s = exp(v0),
   * R = exp([w]x), t = (v4, v5, v6). It is not the sim(3) group exponential;
   * keeping the translation uncoupled makes the update's Jacobians simple.
   */
  static SimilarityTransform exp(const Vector7d& v);

  /// @brief Inverse of exp(): (log s, rotation vector with angle in [0, pi], t).
  Vector7d log() const;

  /// @brief True when the scale is positive and finite and the rotation is proper.
  bool isValid(double toleranceRotation = 1e-6) const;
};

} // namespace vimlop

#endif
