#ifndef vimlop_ModelContourPoint_h
#define vimlop_ModelContourPoint_h

#include <Eigen/Core>

namespace vimlop
{

/**
 * @brief A sample of the model's occluding contour as seen by one camera (V3).
 *
 * `point` lies on a mesh edge with one front-facing and one back-facing face;
 * `normal` is the unit 3-D surface normal there (into the air, the mean of the
 * two faces' normals). `pixel` is its perspective projection and `pixelNormal`
 * the orthographic projection of `normal` onto the image, scaled to pixel
 * axes and normalised: it points from the occluding surface to the occluded,
 * farther side, like a video contour normal.
 */
struct ModelContourPoint
{
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< mm, CT frame
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(); ///< unit, CT frame
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  Eigen::Vector2d pixelNormal = Eigen::Vector2d::UnitX();
  int edge = -1; ///< index into TriangleMesh::edges()
};

} // namespace vimlop

#endif
