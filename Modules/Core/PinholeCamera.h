#ifndef vimlop_PinholeCamera_h
#define vimlop_PinholeCamera_h

#include <vimlop/Core/LensModel.h>

#include <Eigen/Core>

namespace vimlop
{

/**
 * @brief Intrinsics of a pinhole camera in the OpenCV convention.
 *
 * Camera coordinates: x right, y down, z forward, in mm. Pixel coordinates
 * (u, v): u to the right, v down, with the centre of the top-left pixel at
 * (0, 0), so the image covers [-0.5, width - 0.5] x [-0.5, height - 0.5].
 * Lens distortion is kept for bookkeeping only: frames are undistorted when
 * they are loaded, after which projection is the ideal pinhole model.
 */
struct PinholeCamera
{
  double fx = 0.0; ///< focal length along u, pixels
  double fy = 0.0; ///< focal length along v, pixels
  double cx = 0.0; ///< principal point u, pixels
  double cy = 0.0; ///< principal point v, pixels
  int widthPx = 0;
  int heightPx = 0;
  /// OpenCV distortion coefficients, read as `lensModel` says: (k1, k2, p1,
  /// p2[, k3, ...]) or the fisheye's (k1, k2, k3, k4); empty when none.
  Eigen::VectorXd distortion;
  /// How `distortion` is read (default RadialTangential, OpenCV's default
  /// model, so that intrinsics that do not name one read as before).
  LensModel lensModel = LensModel::RadialTangential;

  /// @brief Camera point (mm, z > 0) to pixel. The caller ensures z > 0.
  Eigen::Vector2d project(const Eigen::Vector3d& pointCamera) const
  {
    return { fx * pointCamera.x() / pointCamera.z() + cx,
      fy * pointCamera.y() / pointCamera.z() + cy };
  }

  /// @brief The camera point at depth `depthMm` (along z) that projects to `pixel`.
  Eigen::Vector3d backProject(const Eigen::Vector2d& pixel, double depthMm) const
  {
    return { (pixel.x() - cx) / fx * depthMm, (pixel.y() - cy) / fy * depthMm, depthMm };
  }

  /// @brief Unit direction (camera frame) of the ray through `pixel`.
  Eigen::Vector3d rayDirection(const Eigen::Vector2d& pixel) const
  {
    return backProject(pixel, 1.0).normalized();
  }

  /// @brief True when `pixel` lies in the image, at least `marginPx` inside its border.
  bool isInImage(const Eigen::Vector2d& pixel, double marginPx = 0.0) const
  {
    return pixel.x() >= -0.5 + marginPx && pixel.x() <= widthPx - 0.5 - marginPx &&
      pixel.y() >= -0.5 + marginPx && pixel.y() <= heightPx - 0.5 - marginPx;
  }

  /**
   * @brief True when the lens distorts: a non-zero coefficient of OpenCV's
   * radial-tangential model (k1, k2, p1, p2[, k3, ...]), or a fisheye with
   * coefficients (it bends lines even with k1..k4 = 0: its radius is
   * f theta, not f tan(theta)).
   */
  bool hasDistortion() const;

  /// @brief Makes the camera an ideal pinhole: no coefficients, the default lens model.
  void removeDistortion()
  {
    distortion.resize(0);
    lensModel = LensModel::RadialTangential;
  }

  /**
   * @brief The camera of the same view in a picture `factor` times the size
   * (2: twice as large; 0.5: halved): the focal lengths times `factor`, the
   * size rounded, and the principal point where pixel centres map,
   * (c + 0.5) factor - 0.5, so that a pixel of the resampled picture covers
   * `1 / factor` pixels of this one. The distortion, in normalised
   * coordinates, is kept.
   */
  PinholeCamera resampled(double factor) const;

  /// @brief The 3x3 matrix K = [fx 0 cx; 0 fy cy; 0 0 1].
  Eigen::Matrix3d matrix() const;

  /// @brief Intrinsics from K and the image size; distortion empty.
  static PinholeCamera fromMatrix(const Eigen::Matrix3d& k, int widthPx, int heightPx);

  /**
   * @brief The camera of VIMLOP's simulations (P1's cameras, the virtual
   * endoscope): 320 x 240 pixels, fx = fy = 200 (77° x 62°), principal point
   * at the centre.
   */
  static PinholeCamera simulatedEndoscope();

  /**
   * @brief Checks that the intrinsics are usable.
   * @throws vimlop::Error naming the first problem (non-positive focal length
   * or image size, non-finite value, a focal length under 1/20 or over 20
   * times the image size, which is one in other units than pixels, a
   * principal point far outside the image, a fisheye lens without exactly 4
   * coefficients).
   */
  void validate() const;
};

} // namespace vimlop

#endif
