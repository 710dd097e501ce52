#ifndef vimlop_TrackedVideoWriter_h
#define vimlop_TrackedVideoWriter_h

#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Pipeline/EndoscopeTracker.h>

#include <opencv2/core/mat.hpp>

#include <memory>
#include <string>

namespace vimlop
{

/**
 * @brief Writes the tracked video: every frame with the model's occluding
 * contours that its camera sees at its tracked pose (V3 and V4,
 * visibleModelContours()), under a band with its state. Green when
 * tracking, amber when degraded, red when lost (the contours are then at
 * the prediction): where the drawn contours leave the anatomy's edges, the
 * pose is wrong, whatever the state says. An MJPEG AVI file, as the
 * registered video. No X display is needed (Embree finds the visible
 * contours).
 */
class TrackedVideoWriter
{
public:
  /**
   * @param modelCT the registered model (CT frame, mm)
   * @param camera the pinhole camera of the frames written (undistorted)
   * @param path the video file (.avi)
   * @param fps the video's rate
   * @throws vimlop::Error for a rate that is not positive or invalid intrinsics.
   */
  TrackedVideoWriter(
    const TriangleMesh& modelCT, const PinholeCamera& camera, const std::string& path, double fps);
  ~TrackedVideoWriter();
  TrackedVideoWriter(const TrackedVideoWriter&) = delete;
  TrackedVideoWriter& operator=(const TrackedVideoWriter&) = delete;

  /**
   * @brief Adds `frame` (8-bit BGR, undistorted, of the camera's size) with
   * the contours at `tracked.cameraToCT` and its state as `frameName` says it.
   * @return the picture written (for a caller that also shows it).
   * @throws vimlop::Error for a frame of another size, or when the file
   * cannot be written.
   */
  cv::Mat write(const cv::Mat& frame, const TrackedFrame& tracked, const std::string& frameName);

  /// @brief Frames written so far.
  int framesWritten() const;

private:
  struct Internals;
  std::unique_ptr<Internals> d;
};

} // namespace vimlop

#endif
