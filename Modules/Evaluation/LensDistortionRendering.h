#ifndef vimlop_LensDistortionRendering_h
#define vimlop_LensDistortionRendering_h

#include <vimlop/Core/DepthMap.h>
#include <vimlop/Core/PinholeCamera.h>

#include <opencv2/core/mat.hpp>

namespace vimlop
{

/**
 * @brief Where each pixel of a distorted picture comes from in a pinhole one.
 *
 * For each pixel (u, v) of `distortedCamera`'s image, the pixel of
 * `pinholeCamera` (whose distortion is ignored) that sees the same ray:
 * (u, v) undistorted with `distortedCamera`'s intrinsics and coefficients in
 * its lens model (cv::undistortPoints, or cv::fisheye::undistortPoints for
 * the fisheye, iterated to convergence) and projected by `pinholeCamera`. A CV_32FC2 map for
 * cv::remap; (-1e6, -1e6) where the distortion has no inverse (beyond the radius where strong
 * barrel distortion folds back, where a fisheye pixel's ray is 90° or more off the axis, or where
 * the iteration does not reproduce the pixel within 0.01 px), so that those pixels stay black.
 */
cv::Mat distortedToPinholeMap(
  const PinholeCamera& distortedCamera, const PinholeCamera& pinholeCamera);

/**
 * @brief The pinhole camera (the focal lengths of `distortedCamera`, no
 * distortion, its principal point moved by whole pixels) whose image covers
 * every pixel of distortedToPinholeMap(distortedCamera, ...) with a pixel of
 * margin: barrel distortion (and a fisheye lens still more) shows more of
 * the scene than the pinhole picture of the same size, and the renderer must
 * draw it. At most 4 times the distorted image's size per axis: rays farther
 * out (a fisheye's near 90°) stay black.
 */
PinholeCamera pinholeCameraCovering(const PinholeCamera& distortedCamera);

/**
 * @brief Renders the lens into a pinhole picture: the distorted picture
 * sampled from `pinholePicture` through `map` (distortedToPinholeMap),
 * bilinear, black where the map has no source.
 */
cv::Mat renderLensDistortion(const cv::Mat& pinholePicture, const cv::Mat& map);

/**
 * @brief The depth map of the distorted picture: at each of its pixels the
 * camera z of the surface point that the pixel sees, taken from the pinhole
 * depth map at the nearest pixel of `map` (depths are not interpolated
 * across silhouettes); DepthMap::noSurface() where the map has no source.
 */
DepthMap renderLensDistortion(const DepthMap& pinholeDepth, const cv::Mat& map);

} // namespace vimlop

#endif
