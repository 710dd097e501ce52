#ifndef vimlop_SfmGeometry_h
#define vimlop_SfmGeometry_h

// Private to the Video module (not installed): camera geometry shared by the
// stages of SfmReconstructor.

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>

#include <Eigen/Core>

#include <opencv2/core.hpp>

#include <cmath>
#include <vector>

namespace vimlop::detail
{

inline constexpr double Degree = M_PI / 180.0;

/// OpenCV's 3x3 camera matrix of `k`.
cv::Mat cameraMatrix(const PinholeCamera& k);

Eigen::Vector2d pixelOf(const cv::KeyPoint& k);

/// World-to-camera [R | t] of a camera-to-world pose.
Eigen::Matrix<double, 3, 4> projectionOf(const CameraPose& pose);

/// Linear multi-view triangulation (DLT) from normalised image points.
Eigen::Vector3d triangulate(const std::vector<Eigen::Matrix<double, 3, 4>>& projections,
  const std::vector<Eigen::Vector2d>& normalised);

} // namespace vimlop::detail

#endif
