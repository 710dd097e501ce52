#include <vimlop/Core/RayClearance.h>

#include <vimlop/Core/Error.h>

namespace vimlop
{

double freeLengthAlongRay(const MeshTree& tree, const Eigen::Vector3d& originCT,
  const Eigen::Vector3d& unitDirection, double limitMm, double stepMm)
{
  if (!(stepMm > 0.0) || !(limitMm >= 0.0))
  {
    throw Error("ray clearance: the step must be positive and the limit not negative");
  }
  for (double length = stepMm; length <= limitMm; length += stepMm)
  {
    if (tree.isSegmentOccluded(originCT, originCT + length * unitDirection, 1e-6))
    {
      return length - stepMm;
    }
  }
  return limitMm;
}

} // namespace vimlop
