#include <vimlop/Core/Rotation.h>

#include <Eigen/Dense>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

namespace vimlop
{

Eigen::Matrix3d skew(const Eigen::Vector3d& a)
{
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

Eigen::Matrix3d rotationFromVector(const Eigen::Vector3d& w)
{
  const double theta2 = w.squaredNorm();
  const Eigen::Matrix3d k = skew(w);
  double a;
  double b;
  if (theta2 < 1e-12)
  {
    // Taylor series keeps the result exact to double precision near identity.
    a = 1.0 - theta2 / 6.0;
    b = 0.5 - theta2 / 24.0;
  }
  else
  {
    const double theta = std::sqrt(theta2);
    a = std::sin(theta) / theta;
    b = (1.0 - std::cos(theta)) / theta2;
  }
  return Eigen::Matrix3d::Identity() + a * k + b * k * k;
}

Eigen::Vector3d rotationToVector(const Eigen::Matrix3d& r)
{
  // Eigen's AngleAxis goes through a quaternion, which is stable at 0 and pi.
  const Eigen::AngleAxisd aa(Eigen::Quaterniond(r).normalized());
  double angle = aa.angle();
  Eigen::Vector3d axis = aa.axis();
  if (angle > M_PI)
  {
    angle = 2.0 * M_PI - angle;
    axis = -axis;
  }
  return axis * angle;
}

double rotationAngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b)
{
  return rotationToVector(a.transpose() * b).norm();
}

bool isRotation(const Eigen::Matrix3d& m, double tolerance)
{
  if (!m.allFinite())
  {
    return false;
  }
  const double orthogonality =
    (m.transpose() * m - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  return orthogonality <= tolerance && std::abs(m.determinant() - 1.0) <= 3.0 * tolerance;
}

Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& m)
{
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

Eigen::Matrix3d rotationTowards(
  const Eigen::Matrix3d& from, const Eigen::Matrix3d& to, double fraction)
{
  return nearestRotation(
    rotationFromVector(fraction * rotationToVector(to * from.transpose())) * from);
}

} // namespace vimlop
