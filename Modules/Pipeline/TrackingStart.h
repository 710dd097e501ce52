#ifndef vimlop_TrackingStart_h
#define vimlop_TrackingStart_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/TriangleMesh.h>

#include <opencv2/core/mat.hpp>

#include <string>

namespace vimlop
{

/**
 * @brief Where EndoscopeTracker starts after a registration: the last frame
 * the result registered (its picture, undistorted as it was registered, and
 * its camera pose in the CT), the field stop of the registered frames, the
 * model and the frames' pinhole camera.
 */
struct TrackingStart
{
  TriangleMesh modelCT;
  PinholeCamera intrinsics;
  cv::Mat frame;
  /// Where the frames show the anatomy (CV_8U, non-zero inside the field
  /// stop; FieldOfView::ofSequence() of the registered frames' pictures).
  cv::Mat fieldOfViewMask;
  CameraPose cameraToCT;
  int frameId = 0;
  /// The file (or video frame) the picture came from, when the result says.
  std::string frameSource;
  /// The registration's contour error (mean over its matched contour
  /// points, px): how far this video's contours lie from the model's even
  /// at the registered poses.
  double contourErrorPx = 0.0;
  /// Why the registration flagged its result as a failure; empty when it did not.
  std::string failureReason;

  /**
   * @brief The start from the result folder `folder` (vimlop register's).
   * @throws vimlop::Error when the folder cannot be read as a result, holds
   * no registered frame, or lacks the last frame's picture.
   */
  static TrackingStart fromResult(const std::string& folder);
};

} // namespace vimlop

#endif
