#ifndef vimlop_RegistrationData_h
#define vimlop_RegistrationData_h

#include <vimlop/Core/VideoFrame.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

/**
 * @brief The data side of a registration (V1): SfM points with their noise
 * and the video frames with their contours, all in the SfM frame.
 */
struct RegistrationData
{
  /// SfM points (SfM units).
  std::vector<Eigen::Vector3d> points;
  /// One covariance per point, mm^2 in the SfM axes (see NoiseModel.h).
  std::vector<Eigen::Matrix3d> pointCovariances;
  std::vector<VideoFrame> frames;

  /// @brief Number of contour points over all frames.
  int numberOfContourPoints() const;

  /**
   * @brief Checks the data before a registration.
   * @throws vimlop::Error naming the first problem: no points, a NaN or Inf,
   * a covariance count that differs from the point count or that is not
   * positive definite, invalid intrinsics, a contour normal that is not unit.
   */
  void validate() const;
};

} // namespace vimlop

#endif
