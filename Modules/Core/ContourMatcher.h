#ifndef vimlop_ContourMatcher_h
#define vimlop_ContourMatcher_h

#include <vimlop/Core/ContourPoint.h>
#include <vimlop/Core/KdTree2D.h>
#include <vimlop/Core/ModelContourPoint.h>
#include <vimlop/Core/StableLayout.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

/// @brief Noise model and bound of the oriented 2-D match (V5).
struct ContourMatchOptions
{
  /// Σ2d: covariance of contour positions, px² (default I, the paper's value
  /// for contours detected in video; its synthetic experiment, P1, uses 9 I).
  Matrix2dUnaligned positionCovariancePx2 = Matrix2dUnaligned::Identity();
  /// κ: von Mises concentration of contour normals (default 200, the paper's).
  double kappa = 200.0;
  /// Largest angle between matched normals, degrees (default 45; the paper
  /// imposes a bound without giving its value).
  double maxAngleDeg = 45.0;
};

/// @brief A video contour point and the model contour sample it matches.
struct ContourMatch
{
  int video = -1; ///< index into the frame's video contour
  int model = -1; ///< index into the model contour samples; -1 when unmatched
  /// C2d = ½ eᵀ Σ2d⁻¹ e + κ (1 - n_y · n_x) with e = y - x.
  double cost = 0.0;
  double mahalanobis2 = 0.0;                         ///< eᵀ Σ2d⁻¹ e
  double angleRad = 0.0;                             ///< angle between the two normals
  Eigen::Vector2d errorPx = Eigen::Vector2d::Zero(); ///< e = y - x, pixels
};

/**
 * @brief Matches every video contour point to the model contour sample with
 * the least C2d among those whose normal is within the angle bound (V5).
 *
 * `modelTree` must be built over the pixels of `model`. The search prunes
 * with ½ |e|² / λmax(Σ2d) <= C2d, so it is exact. Video points with no
 * admissible model sample get `model == -1`.
 */
std::vector<ContourMatch> matchContours(const std::vector<ContourPoint>& video,
  const std::vector<ModelContourPoint>& model, const KdTree2D& modelTree,
  const ContourMatchOptions& options);

/// @brief The same matching by exhaustive search (the reference in tests).
std::vector<ContourMatch> matchContoursBruteForce(const std::vector<ContourPoint>& video,
  const std::vector<ModelContourPoint>& model, const ContourMatchOptions& options);

} // namespace vimlop

#endif
