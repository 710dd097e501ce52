#ifndef vimlop_FrameUndistorter_h
#define vimlop_FrameUndistorter_h

#include <vimlop/Core/PinholeCamera.h>

#include <opencv2/core/mat.hpp>

namespace vimlop
{

/**
 * @brief Removes a lens's distortion from frames, in its lens model:
 * cv::undistort, or for the fisheye one remap table built once. Either keeps
 * K, so that the undistorted frames are the ideal pinhole camera of the same
 * fx, fy, cx, cy (black where the lens saw nothing). Without distortion,
 * frames pass through unchanged.
 */
class FrameUndistorter
{
public:
  explicit FrameUndistorter(const PinholeCamera& camera);

  /// @brief True when the camera's lens distorts (frames are then remapped).
  bool distorts() const { return this->Distorted; }

  /// @brief The camera of the undistorted frames: the given one without its distortion.
  PinholeCamera pinhole() const;

  /**
   * @brief `frame` as the pinhole camera sees it.
   * @throws vimlop::Error for a frame of another size than the camera's.
   */
  cv::Mat undistort(const cv::Mat& frame) const;

private:
  PinholeCamera Camera;
  bool Distorted = false;
  bool Fisheye = false;
  cv::Mat Matrix;
  cv::Mat Coefficients;
  cv::Mat MapU;
  cv::Mat MapV;
};

} // namespace vimlop

#endif
