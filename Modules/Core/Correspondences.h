#ifndef vimlop_Correspondences_h
#define vimlop_Correspondences_h

#include <vimlop/Core/ContourMatcher.h>
#include <vimlop/Core/ModelContourPoint.h>
#include <vimlop/Core/RegistrationResult.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

/// @brief What one frame matched at one estimate T (V3-V5, V8).
struct FrameCorrespondences
{
  /// V3, V4: the model contour samples visible from the frame's camera moved by T.
  std::vector<ModelContourPoint> visibleSamples;
  /// V5: one per video contour point; `model` indexes `visibleSamples`.
  std::vector<ContourMatch> matches;
  /// V8: 1 for inliers, one per match.
  std::vector<char> inliers;
  /// Time of this frame's contours, visibility and 2-D match (the other fields stay 0).
  StageTimes times;
};

/**
 * @brief Everything matched at one estimate T, with outliers marked: the
 * input of the pose update (V6) and of the metrics (V12). Per data point i,
 * in the order of RegistrationData::points.
 */
struct Correspondences
{
  std::vector<Eigen::Vector3d> modelPoints; ///< y_i, mm, CT frame (V2)
  std::vector<Eigen::Vector3d> residuals;   ///< d_i = y_i - T(x_i), mm, CT frame
  std::vector<double> costs;                ///< C3d of the match (½|d|² for closest points)
  std::vector<int> faces;                   ///< face of y_i
  std::vector<char> pointInliers;           ///< V8: 1 for inliers
  /// Per frame, in the order of RegistrationData::frames; empty matches when
  /// contours took no part.
  std::vector<FrameCorrespondences> frames;
  /// Time of the stages, frames summed; `updateMs` and `constraintMs` stay 0.
  StageTimes times;
};

} // namespace vimlop

#endif
