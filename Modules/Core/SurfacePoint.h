#ifndef vimlop_SurfacePoint_h
#define vimlop_SurfacePoint_h

#include <Eigen/Core>

namespace vimlop
{

/**
 * @brief A point on a triangle of a mesh, as returned by closest-point queries.
 */
struct SurfacePoint
{
  Eigen::Vector3d point = Eigen::Vector3d::Zero(); ///< mm, mesh frame
  /// Barycentric coordinates on the face's corners (sum to 1).
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  int face = -1;           ///< face index, -1 when no face was found
  double distanceMm = 0.0; ///< Euclidean distance from the query point

  bool isValid() const { return face >= 0; }
};

} // namespace vimlop

#endif
