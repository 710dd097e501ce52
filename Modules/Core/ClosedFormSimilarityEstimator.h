#ifndef vimlop_ClosedFormSimilarityEstimator_h
#define vimlop_ClosedFormSimilarityEstimator_h

#include <vimlop/Core/PoseEstimator.h>

#include <limits>

namespace vimlop
{

/**
 * @brief The update of the trimmed-ICP baseline: the least-squares similarity
 * of the inlier 3-D pairs in closed form (estimateSimilarity()), within the
 * scale bounds. Contour matches are ignored. With fewer than 3 inliers there
 * is nothing to estimate and the current T is returned.
 */
class ClosedFormSimilarityEstimator : public PoseEstimator
{
public:
  /// @param minScale, maxScale the bounds on s (V7; default unbounded)
  explicit ClosedFormSimilarityEstimator(
    double minScale = 0.0, double maxScale = std::numeric_limits<double>::infinity());

  SimilarityTransform estimate(const RegistrationData& data, const Correspondences& matches,
    const SimilarityTransform& current) const override;

private:
  double MinScale;
  double MaxScale;
};

} // namespace vimlop

#endif
