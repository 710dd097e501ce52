#ifndef vimlop_PoseEstimator_h
#define vimlop_PoseEstimator_h

#include <vimlop/Core/Correspondences.h>
#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/SimilarityTransform.h>

namespace vimlop
{

/**
 * @brief One swappable estimation step (V6): with the matches at the current
 * estimate fixed, the next estimate of T.
 *
 * registerVideo() alternates CorrespondenceSearch::find() and estimate();
 * the implementations differ in the cost they minimise: the anisotropic 3-D
 * and oriented 2-D costs (LevenbergMarquardtPoseEstimator, V-IMLOP and IMLP)
 * or the Euclidean distances of the 3-D inliers (ClosedFormSimilarityEstimator,
 * trimmed ICP). Both keep the scale within the bounds (V7).
 */
class PoseEstimator
{
public:
  virtual ~PoseEstimator() = default;

  /**
   * @brief The next T (SfM frame to CT frame) from the inlier matches of
   * `data` in `matches`, found at `current`; may return a non-finite
   * transform when the problem is degenerate (the caller checks).
   */
  virtual SimilarityTransform estimate(const RegistrationData& data, const Correspondences& matches,
    const SimilarityTransform& current) const = 0;
};

} // namespace vimlop

#endif
