#ifndef vimlop_BundleAdjustment_h
#define vimlop_BundleAdjustment_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

/// @brief Solver settings.
struct BundleAdjustmentOptions
{
  int maxIterations = 50;
  /// Residuals beyond this get Huber weights, pixels (default 1.5).
  double huberPx = 1.5;
  /// Stop when the cost decreases by less than this fraction (default 1e-8).
  double relativeTolerance = 1e-8;
  /// Initial Levenberg-Marquardt damping, relative to the diagonal (default 1e-4).
  double initialDamping = 1e-4;
  /// A camera whose largest translation component (of the world-to-camera
  /// translation) is held as well: with a fixed camera at the world origin
  /// this fixes the scale, the last freedom of the gauge (default -1: none;
  /// the damping then holds the scale).
  int scaleCamera = -1;
};

/**
 * @brief Bundle adjustment: camera poses and 3-D points that minimise the
 * robust sum of squared reprojection errors, with fixed intrinsics.
 *
 * This is VIMLOP's own sparse Levenberg-Marquardt on Eigen rather than Ceres:
 * the problems are small (about 30 cameras and a few thousand points), the
 * Schur complement on the 6-parameter camera blocks is a dense matrix of
 * about 180 x 180 that Eigen factors in microseconds, and it keeps SfM free
 * of another dependency (Ceres, glog, gflags) while giving exactly the
 * normal-equation blocks the point covariances are computed from.
 *
 * Camera j maps a world point X to camera coordinates R_j X + t_j (the
 * inverse of its CameraPose); the update is R_j <- exp([dθ]x) R_j,
 * t_j <- t_j + dt, X_i <- X_i + dX. Residuals are Huber-weighted (iteratively
 * reweighted least squares) beyond `huberPx`. The gauge (the similarity that
 * moves everything without changing any projection) is fixed by holding the
 * cameras in `fixedCameras` still; the remaining scale freedom is held by
 * the damping.
 */
class BundleAdjustment
{
public:
  /// @brief One measurement: point `point` seen by camera `camera` at `pixel`.
  struct Observation
  {
    int camera = 0;
    int point = 0;
    Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  };

  /// @brief What the adjustment did.
  struct Summary
  {
    int iterations = 0;
    double initialRmsPx = 0.0; ///< RMS reprojection error before, pixels
    double finalRmsPx = 0.0;   ///< and after
  };

  /**
   * @brief Adjusts `cameras` (camera-to-world poses) and `points` in place.
   *
   * @param intrinsics one per camera.
   * @param fixedCameras indices of cameras held still (at least one for a
   * unique solution).
   * @throws vimlop::Error for out-of-range indices or mismatched sizes.
   */
  static Summary adjust(std::vector<CameraPose>& cameras, std::vector<Eigen::Vector3d>& points,
    const std::vector<PinholeCamera>& intrinsics, const std::vector<Observation>& observations,
    const std::vector<int>& fixedCameras, const BundleAdjustmentOptions& options);

  /// @brief The same with the default options.
  static Summary adjust(std::vector<CameraPose>& cameras, std::vector<Eigen::Vector3d>& points,
    const std::vector<PinholeCamera>& intrinsics, const std::vector<Observation>& observations,
    const std::vector<int>& fixedCameras)
  {
    return adjust(
      cameras, points, intrinsics, observations, fixedCameras, BundleAdjustmentOptions());
  }
};

} // namespace vimlop

#endif
