#ifndef vimlop_CameraPose_h
#define vimlop_CameraPose_h

#include <Eigen/Core>

namespace vimlop
{

/**
 * @brief Pose of a pinhole camera as a camera-to-world rigid transform.
 *
 * The camera frame follows OpenCV: x right, y down, z forward (the optical
 * axis). `rotation` holds the camera axes in world coordinates as columns and
 * `centre` is the optical centre in world coordinates (mm). "World" is the CT
 * frame for registered cameras and the SfM frame for reconstructed ones. A
 * world point y has camera coordinates `rotation^T (y - centre)`.
 */
struct CameraPose
{
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();

  /// @brief World point (mm) to camera coordinates (mm).
  Eigen::Vector3d worldToCamera(const Eigen::Vector3d& pointWorld) const
  {
    return rotation.transpose() * (pointWorld - centre);
  }

  /// @brief Camera coordinates (mm) to world point (mm).
  Eigen::Vector3d cameraToWorld(const Eigen::Vector3d& pointCamera) const
  {
    return rotation * pointCamera + centre;
  }

  /// @brief Unit optical axis (camera z) in world coordinates.
  Eigen::Vector3d viewDirection() const { return rotation.col(2); }

  /// @brief Homogeneous 4x4 camera-to-world matrix.
  Eigen::Matrix4d matrix() const;

  /**
   * @brief Pose from a homogeneous 4x4 camera-to-world matrix.
   * @throws vimlop::Error if the matrix is not a rigid transform (rotation not
   * orthonormal within `toleranceRotation`, last row not (0,0,0,1), non-finite).
   */
  static CameraPose fromMatrix(
    const Eigen::Matrix4d& cameraToWorld, double toleranceRotation = 1e-6);

  /**
   * @brief Camera at `centre` (mm) whose optical axis points at `target` (mm)
   * and whose image "up" (camera -y) is as close as possible to `upHint`.
   * @throws vimlop::Error if target == centre or upHint is parallel to the axis.
   */
  static CameraPose lookAt(
    const Eigen::Vector3d& centre, const Eigen::Vector3d& target, const Eigen::Vector3d& upHint);
};

} // namespace vimlop

#endif
