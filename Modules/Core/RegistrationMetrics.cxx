#include <vimlop/Core/RegistrationMetrics.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>

#include <cmath>

namespace vimlop
{

double targetRegistrationError(const SimilarityTransform& estimate,
  const SimilarityTransform& truth, const std::vector<Eigen::Vector3d>& targetsCT)
{
  if (targetsCT.empty())
  {
    throw Error("target registration error: no targets");
  }
  const SimilarityTransform error = estimate.compose(truth.inverse());
  double sum = 0.0;
  for (const Eigen::Vector3d& y : targetsCT)
  {
    sum += (error.apply(y) - y).norm();
  }
  return sum / static_cast<double>(targetsCT.size());
}

double cameraPositionError(const CameraPose& estimate, const CameraPose& truth)
{
  return (estimate.centre - truth.centre).norm();
}

double cameraAngleErrorDeg(const CameraPose& estimate, const CameraPose& truth)
{
  return rotationAngleBetween(estimate.rotation, truth.rotation) * 180.0 / M_PI;
}

} // namespace vimlop
