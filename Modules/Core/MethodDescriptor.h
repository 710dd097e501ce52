#ifndef vimlop_MethodDescriptor_h
#define vimlop_MethodDescriptor_h

#include <vimlop/Core/RegistrationOptions.h>

namespace vimlop
{

/// @brief How a method matches a data point to the surface (V2).
enum class PointMatching
{
  /// The most likely point under the point's anisotropic covariance (V-IMLOP, IMLP).
  MostLikelyPoint,
  /// The Euclidean closest point (trimmed ICP).
  ClosestPoint
};

/// @brief When a method trims the worst 3-D pairs (V8, RegistrationOptions::trimFraction).
enum class TrimSchedule
{
  /// In a first stage only; a refinement stage after it relies on the
  /// chi-square test alone, so that trimming does not bias the estimate.
  FirstStageOnly,
  /// In every iteration, in a single stage.
  Throughout
};

/// @brief Which estimation step turns matches into the next T (V6).
enum class PoseEstimation
{
  LevenbergMarquardt,  ///< solvePoseUpdate(): anisotropic 3-D and oriented 2-D costs
  ClosedFormSimilarity ///< estimateSimilarity(): Umeyama on the inlier pairs
};

/**
 * @brief What a registration method is made of: the choice of each stage.
 *
 * V-IMLOP and its baselines share every stage and differ only in these
 * choices, so registerVideo() asks the descriptor instead of the method.
 */
struct MethodDescriptor
{
  /// V3-V5: whether video contours take part in matching and the pose update.
  bool usesContours = true;
  PointMatching pointMatching = PointMatching::MostLikelyPoint;
  /// V8: whether the chi-square test marks 3-D outliers (else trimming alone).
  bool chiSquareTest = true;
  TrimSchedule trimming = TrimSchedule::FirstStageOnly;
  /// V10: whether the method can keep the cameras inside the airway (then
  /// RegistrationOptions::anatomicalConstraint switches it on or off).
  bool anatomicalConstraint = true;
  PoseEstimation poseEstimation = PoseEstimation::LevenbergMarquardt;
};

/// @brief The stages of `method`: V-IMLOP uses everything; IMLP leaves the
/// contours out; trimmed ICP matches closest points, trims throughout without
/// the chi-square test, has no anatomical constraint and estimates in closed form.
/// @throws vimlop::Error for a value outside the enum.
MethodDescriptor describeMethod(RegistrationMethod method);

/// @brief True when a registration with `options` keeps the cameras inside
/// the airway: the method can and the options ask for it (V10).
bool usesAnatomicalConstraint(const RegistrationOptions& options);

} // namespace vimlop

#endif
