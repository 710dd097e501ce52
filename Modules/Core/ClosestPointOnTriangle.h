#ifndef vimlop_ClosestPointOnTriangle_h
#define vimlop_ClosestPointOnTriangle_h

#include <Eigen/Core>

namespace vimlop
{

/**
 * @brief Euclidean closest point to `p` on the triangle (a, b, c).
 *
 * Works by Voronoi regions of the corners, edges and interior, so it is exact
 * for degenerate (zero-area) triangles too.
 *
 * @param barycentric if not null, receives the weights (wa, wb, wc) with
 * result = wa a + wb b + wc c.
 */
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
  const Eigen::Vector3d& b, const Eigen::Vector3d& c, Eigen::Vector3d* barycentric = nullptr);

} // namespace vimlop

#endif
