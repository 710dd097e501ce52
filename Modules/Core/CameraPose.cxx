#include <vimlop/Core/CameraPose.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>

#include <Eigen/Dense>

#include <Eigen/Geometry>

namespace vimlop
{

Eigen::Matrix4d CameraPose::matrix() const
{
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = rotation;
  m.topRightCorner<3, 1>() = centre;
  return m;
}

CameraPose CameraPose::fromMatrix(const Eigen::Matrix4d& m, double toleranceRotation)
{
  if (!m.allFinite())
  {
    throw Error("camera pose matrix has non-finite entries");
  }
  if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9)
  {
    throw Error("camera pose matrix: last row is not (0, 0, 0, 1)");
  }
  if (!isRotation(m.topLeftCorner<3, 3>(), toleranceRotation))
  {
    throw Error("camera pose matrix: upper-left 3x3 block is not a rotation");
  }
  CameraPose pose;
  // Re-orthonormalise so that round-off in files does not accumulate.
  pose.rotation = nearestRotation(m.topLeftCorner<3, 3>());
  pose.centre = m.topRightCorner<3, 1>();
  return pose;
}

CameraPose CameraPose::lookAt(
  const Eigen::Vector3d& centre, const Eigen::Vector3d& target, const Eigen::Vector3d& upHint)
{
  const Eigen::Vector3d axis = target - centre;
  if (!(axis.norm() > 0.0))
  {
    throw Error("lookAt: target coincides with the camera centre");
  }
  const Eigen::Vector3d z = axis.normalized();
  // Camera y points down in the image, so it is the part of -up orthogonal to z.
  const Eigen::Vector3d down = -upHint + upHint.dot(z) * z;
  if (!(down.norm() > 1e-9 * upHint.norm()))
  {
    throw Error("lookAt: up hint is parallel to the viewing direction");
  }
  const Eigen::Vector3d y = down.normalized();
  CameraPose pose;
  pose.rotation.col(0) = y.cross(z);
  pose.rotation.col(1) = y;
  pose.rotation.col(2) = z;
  pose.centre = centre;
  return pose;
}

} // namespace vimlop
