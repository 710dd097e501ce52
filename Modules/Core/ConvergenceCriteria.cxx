#include <vimlop/Core/ConvergenceCriteria.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vimlop
{

double meanMatchCost(const IterationRecord& record)
{
  return record.cost3d / std::max(record.pointInliers, 1) +
    record.cost2d / std::max(record.contourInliers, 1);
}

ConvergenceCriteria::ConvergenceCriteria(
  const std::vector<Eigen::Vector3d>& dataPoints, const RegistrationOptions& options)
  : Options(options)
  , BestMeanCost(std::numeric_limits<double>::infinity())
{
  if (dataPoints.empty())
  {
    throw Error("convergence criteria: the point set is empty");
  }
  for (const Eigen::Vector3d& x : dataPoints)
  {
    this->Centroid += x;
  }
  this->Centroid /= static_cast<double>(dataPoints.size());
  double spread = 0.0;
  for (const Eigen::Vector3d& x : dataPoints)
  {
    spread += (x - this->Centroid).squaredNorm();
  }
  this->RadiusMm = std::sqrt(spread / dataPoints.size());
}

bool ConvergenceCriteria::converged(
  const SimilarityTransform& a, const SimilarityTransform& b) const
{
  const double moved = (b.apply(this->Centroid) - a.apply(this->Centroid)).norm();
  const double rotated = rotationAngleBetween(a.rotation, b.rotation) * 180.0 / M_PI;
  const double scaled = std::abs(b.scale / a.scale - 1.0);
  return moved < this->Options.convergenceTranslationMm &&
    rotated < this->Options.convergenceRotationDeg &&
    scaled < this->Options.convergenceScaleRelative;
}

Vector7d ConvergenceCriteria::stepInMm(
  const SimilarityTransform& a, const SimilarityTransform& b) const
{
  const Vector7d change = b.compose(a.inverse()).log();
  Vector7d step;
  step[0] = this->RadiusMm * change[0];
  step.segment<3>(1) = this->RadiusMm * change.segment<3>(1);
  step.tail<3>() = b.apply(this->Centroid) - a.apply(this->Centroid);
  return step;
}

void ConvergenceCriteria::restartStallTracking(const SimilarityTransform& transform)
{
  this->BestMeanCost = std::numeric_limits<double>::infinity();
  this->Best = transform;
  this->IterationsWithoutProgress = 0;
}

bool ConvergenceCriteria::stalled(double meanCost, const SimilarityTransform& transform)
{
  if (meanCost < this->BestMeanCost * (1.0 - this->Options.stallRelativeDecrease))
  {
    this->BestMeanCost = meanCost;
    this->Best = transform;
    this->IterationsWithoutProgress = 0;
    return false;
  }
  return ++this->IterationsWithoutProgress >= this->Options.stallIterations;
}

} // namespace vimlop
