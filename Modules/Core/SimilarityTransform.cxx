#include <vimlop/Core/SimilarityTransform.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>

#include <Eigen/Dense>

#include <cmath>

namespace vimlop
{

CameraPose SimilarityTransform::apply(const CameraPose& pose) const
{
  CameraPose moved;
  moved.rotation = rotation * pose.rotation;
  moved.centre = apply(pose.centre);
  return moved;
}

SimilarityTransform SimilarityTransform::compose(const SimilarityTransform& first) const
{
  SimilarityTransform t;
  t.scale = scale * first.scale;
  t.rotation = rotation * first.rotation;
  t.translation = scale * (rotation * first.translation) + translation;
  return t;
}

SimilarityTransform SimilarityTransform::inverse() const
{
  SimilarityTransform t;
  t.scale = 1.0 / scale;
  t.rotation = rotation.transpose();
  t.translation = -(rotation.transpose() * translation) / scale;
  return t;
}

Eigen::Matrix4d SimilarityTransform::matrix() const
{
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = scale * rotation;
  m.topRightCorner<3, 1>() = translation;
  return m;
}

SimilarityTransform SimilarityTransform::fromMatrix(
  const Eigen::Matrix4d& m, double toleranceRotation)
{
  if (!m.allFinite())
  {
    throw Error("similarity matrix has non-finite entries");
  }
  if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9)
  {
    throw Error("similarity matrix: last row is not (0, 0, 0, 1)");
  }
  const Eigen::Matrix3d a = m.topLeftCorner<3, 3>();
  const double det = a.determinant();
  if (!(det > 0.0))
  {
    throw Error("similarity matrix: upper-left 3x3 block has non-positive determinant");
  }
  SimilarityTransform t;
  t.scale = std::cbrt(det);
  if (!isRotation(a / t.scale, toleranceRotation))
  {
    throw Error("similarity matrix: upper-left 3x3 block is not a scaled rotation");
  }
  t.rotation = nearestRotation(a / t.scale);
  t.translation = m.topRightCorner<3, 1>();
  return t;
}

SimilarityTransform SimilarityTransform::exp(const Vector7d& v)
{
  SimilarityTransform t;
  t.scale = std::exp(v[0]);
  t.rotation = rotationFromVector(v.segment<3>(1));
  t.translation = v.tail<3>();
  return t;
}

Vector7d SimilarityTransform::log() const
{
  Vector7d v;
  v[0] = std::log(scale);
  v.segment<3>(1) = rotationToVector(rotation);
  v.tail<3>() = translation;
  return v;
}

bool SimilarityTransform::isValid(double toleranceRotation) const
{
  return std::isfinite(scale) && scale > 0.0 && translation.allFinite() &&
    isRotation(rotation, toleranceRotation);
}

} // namespace vimlop
