#ifndef vimlop_SimilarityEstimation_h
#define vimlop_SimilarityEstimation_h

#include <vimlop/Core/SimilarityTransform.h>

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace vimlop
{

/**
 * @brief Least-squares similarity T minimising Σ |target_i - T(source_i)|²
 * (Umeyama's closed form), with the scale clamped to [minScale, maxScale]
 * (the best rotation does not depend on the scale; the translation is
 * recomputed for the clamped one). Used by the trimmed-ICP baseline.
 * @throws vimlop::Error for fewer than 3 pairs or mismatched sizes.
 */
SimilarityTransform estimateSimilarity(const std::vector<Eigen::Vector3d>& source,
  const std::vector<Eigen::Vector3d>& target, double minScale = 0.0,
  double maxScale = std::numeric_limits<double>::infinity());

} // namespace vimlop

#endif
