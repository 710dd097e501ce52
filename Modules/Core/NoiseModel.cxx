#include <vimlop/Core/NoiseModel.h>

#include <vimlop/Core/Error.h>

#include <Eigen/Dense>

#include <cmath>

namespace vimlop
{

Eigen::Matrix3d isotropicCovariance(double sigmaMm)
{
  return sigmaMm * sigmaMm * Eigen::Matrix3d::Identity();
}

Eigen::Matrix3d viewAlignedCovariance(
  const Eigen::Vector3d& viewDirection, double sigmaAlongMm, double sigmaAcrossMm)
{
  const double n = viewDirection.norm();
  if (!(n > 0.0) || !std::isfinite(n))
  {
    throw Error("view-aligned noise needs a non-zero, finite viewing direction");
  }
  if (!(sigmaAlongMm >= 0.0) || !(sigmaAcrossMm >= 0.0))
  {
    throw Error("noise standard deviations must not be negative");
  }
  const Eigen::Vector3d v = viewDirection / n;
  return sigmaAcrossMm * sigmaAcrossMm * Eigen::Matrix3d::Identity() +
    (sigmaAlongMm * sigmaAlongMm - sigmaAcrossMm * sigmaAcrossMm) * v * v.transpose();
}

std::string covarianceProblem(const Eigen::Matrix3d& c)
{
  if (!c.allFinite())
  {
    return "has non-finite entries";
  }
  if ((c - c.transpose()).cwiseAbs().maxCoeff() > 1e-9 * std::max(1.0, c.cwiseAbs().maxCoeff()))
  {
    return "is not symmetric";
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(c, Eigen::EigenvaluesOnly);
  // Relative floor: a covariance whose smallest axis is 1e-12 of its largest
  // cannot be whitened reliably.
  if (!(eig.eigenvalues()[0] > 1e-12 * std::max(eig.eigenvalues()[2], 1e-300)))
  {
    return "is not positive definite";
  }
  return std::string();
}

const char* toString(PointNoiseModel model)
{
  switch (model)
  {
    case PointNoiseModel::Isotropic:
      return "isotropic";
    case PointNoiseModel::ViewAligned:
      return "view-aligned";
    case PointNoiseModel::PerPoint:
      return "per-point";
  }
  return "unknown";
}

} // namespace vimlop
