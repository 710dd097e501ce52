#include <vimlop/Core/ClosedFormSimilarityEstimator.h>

#include <vimlop/Core/SimilarityEstimation.h>

namespace vimlop
{

ClosedFormSimilarityEstimator::ClosedFormSimilarityEstimator(double minScale, double maxScale)
  : MinScale(minScale)
  , MaxScale(maxScale)
{
}

SimilarityTransform ClosedFormSimilarityEstimator::estimate(const RegistrationData& data,
  const Correspondences& matches, const SimilarityTransform& current) const
{
  std::vector<Eigen::Vector3d> source;
  std::vector<Eigen::Vector3d> target;
  for (size_t i = 0; i < matches.modelPoints.size(); ++i)
  {
    if (matches.pointInliers[i])
    {
      source.push_back(data.points[i]);
      target.push_back(matches.modelPoints[i]);
    }
  }
  if (source.size() < 3)
  {
    return current;
  }
  return estimateSimilarity(source, target, this->MinScale, this->MaxScale);
}

} // namespace vimlop
