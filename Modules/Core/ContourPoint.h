#ifndef vimlop_ContourPoint_h
#define vimlop_ContourPoint_h

#include <Eigen/Core>

namespace vimlop
{

/**
 * @brief An oriented 2-D contour feature of a video frame (V1).
 *
 * `pixel` uses the OpenCV pixel convention (see PinholeCamera). `normal` is a
 * unit 2-D vector in pixel axes (u right, v down) pointing from the
 * occluding, nearer surface to the occluded, farther side: in video, the
 * negative intensity gradient.
 */
struct ContourPoint
{
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
};

} // namespace vimlop

#endif
