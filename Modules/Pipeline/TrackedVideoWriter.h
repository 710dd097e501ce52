#ifndef vimlop_TrackedVideoWriter_h
#define vimlop_TrackedVideoWriter_h

#include <vimlop/Core/ModelContourPoint.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Pipeline/EndoscopeTracker.h>

#include <opencv2/core/mat.hpp>

#include <memory>
#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief Writes the tracked video: every frame with the model's occluding
 * contours that its camera sees at its tracked pose (V3 and V4,
 * visibleModelContours(), e.g. from FrameContourCheck), under a band with its
 * state and contour error. Green when
 * tracking, amber when degraded, red when lost (the contours are then at
 * the prediction): where the drawn contours leave the anatomy's edges, the
 * pose is wrong, whatever the state says. An MJPEG AVI file, as the
 * registered video.
 */
class TrackedVideoWriter
{
public:
  /**
   * @param camera the pinhole camera of the frames written (undistorted)
   * @param path the video file (.avi)
   * @param fps the video's rate
   * @throws vimlop::Error for a rate that is not positive or invalid intrinsics.
   */
  TrackedVideoWriter(const PinholeCamera& camera, const std::string& path, double fps);
  ~TrackedVideoWriter();
  TrackedVideoWriter(const TrackedVideoWriter&) = delete;
  TrackedVideoWriter& operator=(const TrackedVideoWriter&) = delete;

  /**
   * @brief Adds `frame` (8-bit BGR, undistorted, of the camera's size) with
   * `modelContours` (the model's visible contours at `tracked.cameraToCT`)
   * and its state as `frameName` says it, with the contours' median error
   * (px) when it is a number.
   * @return the picture written (for a caller that also shows it).
   * @throws vimlop::Error for a frame of another size, or when the file
   * cannot be written.
   */
  cv::Mat write(const cv::Mat& frame, const TrackedFrame& tracked, const std::string& frameName,
    const std::vector<ModelContourPoint>& modelContours, double contourErrorPx);

  /// @brief Frames written so far.
  int framesWritten() const;

private:
  struct Internals;
  std::unique_ptr<Internals> d;
};

} // namespace vimlop

#endif
