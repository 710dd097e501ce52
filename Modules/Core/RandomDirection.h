#ifndef vimlop_RandomDirection_h
#define vimlop_RandomDirection_h

#include <Eigen/Core>

#include <random>

namespace vimlop
{

/**
 * @brief A unit vector drawn uniformly over the sphere (a normalised
 * standard normal 3-vector) from `rng`: the axis of a random rotation or
 * the direction of a random shift. The same engine state gives the same
 * vector, so seeded simulations are reproducible.
 */
Eigen::Vector3d randomDirection(std::mt19937_64& rng);

} // namespace vimlop

#endif
