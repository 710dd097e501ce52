#ifndef vimlop_RegistrationResult_h
#define vimlop_RegistrationResult_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/SimilarityTransform.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

/// @brief Why a registration stopped (V11).
enum class TerminationReason
{
  Converged,       ///< the change of T fell below every threshold
  Stalled,         ///< the match cost stopped decreasing; the lowest-cost estimate is kept
  MaxIterations,   ///< the iteration cap was reached
  Cancelled,       ///< the iteration callback asked to stop
  NumericalFailure ///< the update produced a non-finite transform; the last valid one is kept
};

/// @brief "converged", "max-iterations", "cancelled" or "numerical-failure".
const char* toString(TerminationReason reason);

/// @brief Wall-clock time of each stage of one iteration, milliseconds (frames summed).
struct StageTimes
{
  double match3dMs = 0.0;    ///< V2
  double contoursMs = 0.0;   ///< V3
  double visibilityMs = 0.0; ///< V4
  double match2dMs = 0.0;    ///< V5
  double outliersMs = 0.0;   ///< V8
  double updateMs = 0.0;     ///< V6, V7
  double constraintMs = 0.0; ///< V10
};

/// @brief What one iteration did (V12 history). Metrics are at `transform`,
/// the estimate the iteration matched with; `updated` is what it produced.
struct IterationRecord
{
  int iteration = 0;
  /// Whether contours took part (see RegistrationOptions::pointsFirst).
  bool withContours = false;
  SimilarityTransform transform;
  SimilarityTransform updated;
  double cost = 0.0; ///< Σ C3d + Σ C2d over inliers, before the update
  double cost3d = 0.0;
  double cost2d = 0.0;
  int pointInliers = 0;
  int contourMatches = 0;
  int contourInliers = 0;
  double residualErrorMm = 0.0; ///< mean |y - T(x)| over 3-D inliers
  double contourErrorPx = 0.0;  ///< mean |e| over matched contour points
  /// V10 halvings applied to this update; maxBackoffSteps + 1 when it was undone.
  int backoffSteps = 0;
  /// Extrapolation factor applied after the update (0: none); see RegistrationOptions::accelerate.
  double acceleration = 0.0;
  /// True when this iteration found the previous extrapolation worse and undid it.
  bool extrapolationUndone = false;
  StageTimes times;
};

/// @brief A video contour point, its model match and whether it is an inlier.
struct ContourCorrespondence
{
  int video = -1;
  Eigen::Vector2d videoPixel = Eigen::Vector2d::Zero();
  Eigen::Vector2d modelPixel = Eigen::Vector2d::Zero();
  Eigen::Vector3d modelPoint = Eigen::Vector3d::Zero(); ///< mm, CT frame
  bool inlier = false;
};

/// @brief Per-frame outcome.
struct FrameResult
{
  int frameId = 0;
  CameraPose cameraToCT;
  int contourPoints = 0; ///< video contour points of the frame
  int matched = 0;       ///< of which have a model match
  int inliers = 0;
  double contourErrorPx = 0.0;        ///< mean |e| over matched points
  double contourErrorInliersPx = 0.0; ///< mean |e| over inliers
  int visibleModelSamples = 0;
  std::vector<ContourCorrespondence> correspondences;
};

/// @brief The result of a registration (V12).
struct RegistrationResult
{
  /// T: SfM frame to CT frame.
  SimilarityTransform sfmToCT;
  std::vector<FrameResult> frames;
  /// 1 for 3-D inliers at the final estimate.
  std::vector<char> pointInliers;
  /// The model point each SfM point matched at the final estimate (mm, CT).
  std::vector<Eigen::Vector3d> pointMatches;
  std::vector<IterationRecord> history;
  /// Mean distance of registered 3-D inliers to the surface, mm.
  double residualErrorMm = 0.0;
  /// Mean distance of matched contour pairs over all frames, pixels: all matches, and inliers.
  double contourErrorPx = 0.0;
  double contourErrorInliersPx = 0.0;
  TerminationReason termination = TerminationReason::MaxIterations;
  int iterations = 0;
  double runtimeSeconds = 0.0;
};

} // namespace vimlop

#endif
