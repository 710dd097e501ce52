#ifndef vimlop_LensModel_h
#define vimlop_LensModel_h

namespace vimlop
{

/**
 * @brief The lens distortion model of a camera's coefficients
 * (PinholeCamera::distortion), as OpenCV calibrates them.
 *
 * The model only tells how to read the coefficients; without coefficients
 * the camera is an ideal pinhole whatever the model.
 */
enum class LensModel
{
  /// OpenCV's default ("Brown", ROS's "plumb_bob"): k1, k2, p1, p2[, k3[, k4, k5, k6]].
  RadialTangential,
  /// OpenCV's cv::fisheye (equidistant, Kannala–Brandt; ROS's "equidistant"):
  /// exactly k1, k2, k3, k4, with theta_d = theta (1 + k1 theta^2 + k2 theta^4
  /// + k3 theta^6 + k4 theta^8) the distorted radius (normalised) of a ray at
  /// angle theta from the optical axis.
  Fisheye
};

} // namespace vimlop

#endif
