#ifndef vimlop_SfmReconstruction_h
#define vimlop_SfmReconstruction_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief A structure-from-motion reconstruction of a frame sequence: 3-D
 * points with covariances and the camera of every frame, in the SfM frame.
 *
 * The SfM frame is known only up to a similarity: lengths are in SfM units
 * (for the built-in SfM, one unit is the mean distance between consecutive
 * registered cameras), which the registration scales to mm. Cameras follow
 * VIMLOP's conventions (CameraPose: camera-to-SfM, OpenCV axes; PinholeCamera
 * pixels with the centre of the top-left pixel at (0, 0)). Frames that SfM
 * could not register keep `registered == false` and an identity pose.
 */
struct SfmReconstruction
{
  /// @brief One image of the sequence.
  struct Frame
  {
    /// Name of the image (file name in the frame folder).
    std::string name;
    bool registered = false;
    CameraPose cameraToSfm;
    PinholeCamera intrinsics;
  };

  /// @brief A 2-D measurement of a point in a frame (pixels).
  struct Observation
  {
    int frame = -1; ///< index into `frames`
    Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  };

  /// @brief A reconstructed point.
  struct Point
  {
    Eigen::Vector3d position = Eigen::Vector3d::Zero(); ///< SfM units
    /// Positional covariance, SfM units², SfM axes.
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
    /// Colour of the point (8-bit RGB), for display.
    Eigen::Vector3i colour = Eigen::Vector3i::Zero();
    std::vector<Observation> observations;
    /// RMS reprojection error over the observations, pixels.
    double reprojectionErrorPx = 0.0;
  };

  std::vector<Frame> frames;
  std::vector<Point> points;
  /// Where it came from: "builtin" or "colmap".
  std::string source = "builtin";
  /// mm per SfM unit from an electromagnetic tracker (V14); 0 when unknown.
  double trackerScale = 0.0;

  int numberOfRegisteredFrames() const;

  /// @brief RMS reprojection error over every observation, pixels (recomputed
  /// from the points, poses and intrinsics).
  double rmsReprojectionErrorPx() const;

  /**
   * @brief Fills in each point's covariance from its observations and the
   * camera geometry (see triangulationCovariance()), with an image noise of
   * `sigmaPx` pixels, and its reprojection error.
   */
  void computeCovariances(double sigmaPx);

  /**
   * @brief Covariance of a point triangulated from the given observations by
   * cameras that are taken as exact: sigma² (Jᵀ J)⁻¹ with J the Jacobian of
   * the projections with respect to the point (SfM units², SfM axes). It is
   * elongated along the viewing rays, the more so the smaller their angles.
   * Returns a large isotropic matrix when the rays are (nearly) parallel.
   */
  Eigen::Matrix3d triangulationCovariance(const Eigen::Vector3d& position,
    const std::vector<Observation>& observations, double sigmaPx) const;

  /**
   * @brief Checks the indices and values.
   * @throws vimlop::Error naming the first problem (a point observed by a
   * frame that does not exist or is not registered, non-finite values).
   */
  void validate() const;

  /**
   * @brief This reconstruction with its frames in the order of `names`: a
   * name it lacks becomes an unregistered frame; its frames not named are
   * dropped with their observations (and points left with fewer than two);
   * `warnings`, when given, receives what was dropped or is missing.
   */
  SfmReconstruction forFrames(
    const std::vector<std::string>& names, std::vector<std::string>* warnings = nullptr) const;
};

} // namespace vimlop

#endif
