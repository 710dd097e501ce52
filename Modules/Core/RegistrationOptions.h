#ifndef vimlop_RegistrationOptions_h
#define vimlop_RegistrationOptions_h

#include <vimlop/Core/ContourMatcher.h>
#include <vimlop/Core/PoseUpdate.h>

#include <limits>
#include <string>

namespace vimlop
{

/// @brief Which algorithm registerVideo() runs; the baselines share its stages.
enum class RegistrationMethod
{
  VIMLOP,    ///< 3-D points and oriented 2-D contours (the paper's V-IMLOP)
  IMLP,      ///< V-IMLOP without contours: anisotropic 3-D points only
  TrimmedICP ///< Euclidean closest points, trimming, closed-form similarity
};

/// @brief Name of a method as used on the command line: "vimlop", "imlp", "trimmed-icp".
const char* toString(RegistrationMethod method);
/// @brief "vimlop", "imlp" or "trimmed-icp" as a method. @throws vimlop::Error for others.
RegistrationMethod registrationMethodFromString(const std::string& name);

/**
 * @brief Every parameter of a registration, with the paper's values where it
 * gives them. Units: mm, pixels, radians (degrees only in the names that say so).
 * Each scalar setting also has a row in RegistrationOptionTable.h (its
 * range, JSON key, flag and VTK name).
 */
struct RegistrationOptions
{
  RegistrationMethod method = RegistrationMethod::VIMLOP;

  /// V5: Σ2d (default 1 px² I), κ (default 200) and the normal-angle bound (default 45°).
  ContourMatchOptions contourMatch;
  /// V3: spacing of model contour samples along their edges, pixels (default 1).
  double contourSampleSpacingPx = 1.0;

  /// V7: bounds on the scale s (SfM units to mm); default unbounded. The
  /// initial scale must lie within them.
  double minScale = 0.0;
  double maxScale = std::numeric_limits<double>::infinity();

  /// V8: the initial trim ratio p_t: the fraction of 3-D pairs with the
  /// highest cost trimmed in each iteration of the first stage (until the
  /// first convergence, or half the iteration cap);
  /// the refinement after it relies on the chi-square test alone, so that
  /// trimming does not bias the final estimate on clean data (trimmed ICP
  /// trims throughout). Default 0.1; the paper does not state its value.
  double trimFraction = 0.1;
  /// V8: probability p of the chi-square outlier tests (default 0.95).
  double chiSquareProbability = 0.95;
  /// V8: at most this fraction of a frame's contour points are outliers (default 0.5).
  double maxContourOutlierFraction = 0.5;
  /// V8: the contour tests' variance inflation from the median squared
  /// distance and angle of the matches (scaled to a Gaussian's mean) rather
  /// than their means (contourErrorSpread()), so that contours the model
  /// lacks cannot widen the test that should reject them. The paper does not
  /// say how it inflates. Default off: it helps under model error (P1, 50
  /// trials, seed 2: median TRE 0.540 -> 0.452 mm with data at +100 HU,
  /// 0.201 -> 0.175 mm from the undecimated surface) but costs in the ideal
  /// world with a field stop (the demo's frames in an image circle: 0.033 ->
  /// 0.068 mm). See Documentation/Algorithm.md, V8.
  bool robustContourInflation = false;

  /// V9: scale the 3-D covariances by n3d (1 - p_t) / n2d (default on).
  bool equalInfluence = true;

  /// V10: keep every camera inside the surface (default on; never for trimmed ICP).
  bool anatomicalConstraint = true;
  /// V10: halvings of the last change tried before the change is undone (default 10).
  int maxBackoffSteps = 10;

  /// V11: iteration cap (default 300; see stallRelativeDecrease).
  int maxIterations = 300;
  /// V11: converged when the data centroid moves less than this, mm (default 0.005) ...
  double convergenceTranslationMm = 5e-3;
  /// ... and the rotation changes less than this, degrees (default 0.005) ...
  double convergenceRotationDeg = 5e-3;
  /// ... and the scale changes by less than this fraction (default 2e-4: 0.004 mm
  /// over a 20 mm wide reconstruction, like the translation threshold).
  double convergenceScaleRelative = 2e-4;

  /**
   * Extrapolate along the path of the estimates when successive updates point
   * the same way (within 10°), by the remaining sum of their geometric
   * decrease (at most `maxAcceleration` times the last update), as in Besl
   * and McKay's accelerated ICP. An extrapolation that raises the mean match
   * cost is undone at the next iteration. It changes how fast the iterations
   * approach the solution, not the solution. Default on.
   */
  bool accelerate = true;
  double maxAcceleration = 10.0;

  /// V11: stop when the mean match cost per inlier has not fallen by this
  /// fraction (default 1e-5) below its lowest value for `stallIterations`
  /// iterations (default 10); the lowest-cost estimate is returned. With
  /// about 1500 SfM points and thousands of contour points accurate to a
  /// fraction of a pixel, the cost of a video registration falls slowly near
  /// the optimum, and a looser rule (0.1 % in 5 iterations, which P1's small
  /// synthetic problems use) ends the run before the estimate settles; the
  /// change thresholds then decide convergence.
  double stallRelativeDecrease = 1e-5;
  int stallIterations = 10;

  /**
   * V-IMLOP: leave the contours out of the first stage (until the first
   * convergence) and add them for the refinement. The paper does not say how
   * its iterations start; with contours from the first iteration, a start a
   * few millimetres off matches video contours to the wrong model edges, and
   * those matches can hold the estimate in a wrong valley (P1, 20 trials:
   * 95th percentile TRE 1.1 mm without, 0.13 mm with). Default on.
   */
  bool pointsFirst = true;

  /// V6: the Levenberg-Marquardt solver of the pose update.
  PoseUpdateOptions poseUpdate;

  /// Threads, 0 for all cores (default 0). Results do not depend on it.
  int threads = 0;

  /**
   * @brief Checks the values: the scale bounds' order, Σ2d, and every
   * setting of RegistrationOptionTable.h against its range.
   * @throws vimlop::Error naming the first invalid one (e.g. min scale > max scale).
   */
  void validate() const;
};

} // namespace vimlop

#endif
