#ifndef vimlop_FrameContourCheck_h
#define vimlop_FrameContourCheck_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/ContourMatcher.h>
#include <vimlop/Core/ContourPoint.h>
#include <vimlop/Core/ModelContourPoint.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/PoseUpdate.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Video/ContourDetectionOptions.h>

#include <opencv2/core/mat.hpp>

#include <limits>
#include <memory>
#include <vector>

namespace vimlop
{

/// @brief How a frame's own occluding contours agree with the model's at a pose.
struct FrameContourAgreement
{
  /// Contour points detected in the frame, inside the field stop (V1).
  int detected = 0;
  /// Of those, the ones matched to a visible model contour sample (V5: the
  /// registration's oriented match, normals within its angle bound).
  int matched = 0;
  /// Median distance |e| of the matched points to their model samples, px;
  /// NaN when none matched. A median, not the registration's mean over its
  /// inliers: one frame has no outlier model of its own, and a video edge
  /// that the model lacks matches a far sample.
  double medianErrorPx = std::numeric_limits<double>::quiet_NaN();
  /// The model's visible occluding contours at the pose (V3, V4).
  std::vector<ModelContourPoint> modelContours;
  /// The matches that are not outliers, as the pose update takes them (V6;
  /// `frame` 0): those within 3 times the median distance, or 2 px. (The
  /// matcher pairs every detected point with some model sample; a video edge
  /// the model lacks pairs with a far one.)
  std::vector<ContourPair> pairs;
};

/**
 * @brief A check of a tracked pose against the CT: the frame's occluding
 * contours, detected as the registration detects them, matched to the
 * model's at the pose (issue 16: the contour error of every tracked frame).
 *
 * The features the tracker follows stand for model points cast from poses
 * it found itself, so they cannot tell when those poses drift; the contours
 * come from the picture and the CT alone. Where the model is the truth and
 * the pose is right, the median error is about a pixel; it grows as the pose
 * leaves the truth (Documentation/Tracking.md gives what was measured).
 */
class FrameContourCheck
{
public:
  /**
   * @param model the registered model (shared, e.g. with the tracked video)
   * @param camera the pinhole camera of the frames checked (undistorted)
   * @param fieldOfViewMask where contours may be detected (CV_8U, non-zero
   * inside the field stop; empty: everywhere)
   * @throws vimlop::Error for invalid intrinsics, or a mask of another size.
   */
  FrameContourCheck(const RegistrationModel& model, const PinholeCamera& camera,
    const cv::Mat& fieldOfViewMask, const ContourDetectionOptions& detection = {},
    const ContourMatchOptions& matching = {});
  ~FrameContourCheck();
  FrameContourCheck(const FrameContourCheck&) = delete;
  FrameContourCheck& operator=(const FrameContourCheck&) = delete;

  /**
   * @brief The agreement of `frame` (8-bit BGR, undistorted, of the camera's
   * size) with the model seen from `cameraToCT`.
   * @throws vimlop::Error for a frame of another size.
   */
  FrameContourAgreement check(const cv::Mat& frame, const CameraPose& cameraToCT) const;

  /**
   * @brief The occluding contours of `frame` inside the field stop (V1), as
   * check() detects them: detected once, they can be matched at many poses.
   * @throws vimlop::Error for a frame of another size.
   */
  std::vector<ContourPoint> detect(const cv::Mat& frame) const;

  /// @brief The agreement of contours detect() found with the model seen from `cameraToCT`.
  FrameContourAgreement agreement(
    const std::vector<ContourPoint>& detected, const CameraPose& cameraToCT) const;

  /// @brief The pinhole camera of the frames checked.
  const PinholeCamera& camera() const;

  /// @brief The model checked against.
  const RegistrationModel& model() const;

private:
  struct Internals;
  std::unique_ptr<Internals> d;
};

} // namespace vimlop

#endif
