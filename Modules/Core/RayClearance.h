#ifndef vimlop_RayClearance_h
#define vimlop_RayClearance_h

#include <vimlop/Core/MeshTree.h>

#include <Eigen/Core>

namespace vimlop
{

/**
 * @brief How far a ray runs through free space before it meets the model
 * surface, measured by walking: the longest tested length `k * stepMm`
 * (k = 1, 2, ...) up to `limitMm` whose segment from `originCT` is not
 * occluded by the surface (MeshTree::isSegmentOccluded) is returned; 0 when the
 * first step already hits it, `limitMm` when the whole ray is free.
 *
 * The walk is coarse on purpose: callers only compare the free length with a
 * distance they need, and the step sets how exactly. Each caller states its
 * step: camera paths of the synthetic experiment walk 1 mm steps, the
 * endoscope trajectory 0.5 mm steps (its sway leaves less room), and the
 * canonical views test their whole look-ahead in one step (they only ask
 * whether it is free).
 *
 * @param originCT start of the ray, mm, CT frame
 * @param unitDirection direction of the ray, unit length, CT frame
 * @param limitMm longest length walked, mm (not negative)
 * @param stepMm step of the walk, mm (positive)
 * @throws vimlop::Error for a step that is not positive or a negative limit.
 */
double freeLengthAlongRay(const MeshTree& tree, const Eigen::Vector3d& originCT,
  const Eigen::Vector3d& unitDirection, double limitMm, double stepMm);

} // namespace vimlop

#endif
