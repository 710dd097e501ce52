#ifndef vimlop_OutlierRejection_h
#define vimlop_OutlierRejection_h

#include <vimlop/Core/ContourMatcher.h>

#include <Eigen/Core>

#include <vector>

/**
 * @file OutlierRejection.h
 * @brief Outlier tests between matching and the pose update (V8).
 */

namespace vimlop
{

struct FrameCorrespondences;

/**
 * @brief Marks 3-D outliers: first the fraction `trimFraction` of pairs with
 * the highest match cost, then, among the rest, every pair with
 * dᵀ R (Σ + σ² I)⁻¹ Rᵀ d > `chiSquareThreshold` (χ²₃(p)), σ² the mean squared
 * match distance |d|² of the pairs the trimming kept.
 *
 * @param residualsCT d = y - T(x) per pair (mm, CT frame)
 * @param covariances Σ per pair (mm², SfM axes, as used for matching)
 * @param rotation R of the current transform
 * @param matchCosts C3d per pair (the trimming order)
 * @return 1 for inliers, 0 for outliers
 */
std::vector<char> rejectPointOutliers(const std::vector<Eigen::Vector3d>& residualsCT,
  const std::vector<Eigen::Matrix3d>& covariances, const Eigen::Matrix3d& rotation,
  const std::vector<double>& matchCosts, double trimFraction, double chiSquareThreshold);

/**
 * @brief Marks the outliers among one frame's contour matches.
 *
 * Two independent tests, like the 3-D one with its variance inflation: the
 * position test eᵀ (Σ2d + σe² I)⁻¹ e > χ²₂(p), and the orientation test by the
 * normal approximation of the von Mises distribution θ² / (1/κ + σθ²) > χ²₁(p),
 * with σe² and σθ² the spread of every frame's current contour matches
 * (contourErrorSpread()). If more than
 * `maxOutlierFraction` of the frame's matched points fail, only that many
 * (the worst) are rejected. Unmatched points are outliers.
 *
 * @return 1 for inliers, 0 for outliers, one per match
 */
std::vector<char> rejectContourOutliers(const std::vector<ContourMatch>& matches,
  const ContourMatchOptions& matchOptions, double squaredDistancePx2, double squaredAngleRad2,
  double chiSquareProbability, double maxOutlierFraction);

/// @brief The variance inflation of the contour tests: σe² (px²) and σθ² (rad²).
struct ContourErrorSpread
{
  double squaredDistancePx2 = 0.0;
  double squaredAngleRad2 = 0.0;
};

/**
 * @brief σe² and σθ² of the matched contour points of every frame (0 when
 * none matched): their mean squared distance |e|² and angle θ², or, `robust`,
 * the medians scaled to those means for Gaussian errors (|e|² ~ σ² χ²₂ and
 * θ² ~ σ² χ²₁: median / χ²_k(0.5) · k). The medians are not set by the
 * outliers the tests look for: a video contour with no counterpart on the
 * model (a structure the model lacks) matches a far sample, and with the
 * means a few of those widen the test until they pass it.
 */
ContourErrorSpread contourErrorSpread(const std::vector<FrameCorrespondences>& frames, bool robust);

} // namespace vimlop

#endif
