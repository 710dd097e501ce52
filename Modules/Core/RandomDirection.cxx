#include <vimlop/Core/RandomDirection.h>

namespace vimlop
{

Eigen::Vector3d randomDirection(std::mt19937_64& rng)
{
  std::normal_distribution<double> normal;
  Eigen::Vector3d v;
  // A draw this close to the origin has no usable direction: draw again.
  do
  {
    v = Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  } while (v.norm() < 1e-9);
  return v.normalized();
}

} // namespace vimlop
