#ifndef vimlop_RandomGeometry_h
#define vimlop_RandomGeometry_h

// Random rotations, covariances and transforms for property tests.

#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/SimilarityTransform.h>

#include <Eigen/Dense>

#include <random>

namespace vimlop::fixtures
{

inline Eigen::Vector3d randomUnit(std::mt19937& rng)
{
  std::normal_distribution<double> n;
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

inline Eigen::Matrix3d randomRotation(std::mt19937& rng)
{
  std::uniform_real_distribution<double> angle(0.0, M_PI);
  return rotationFromVector(angle(rng) * randomUnit(rng));
}

/// SPD covariance with standard deviations in [minStd, maxStd] along random axes.
inline Eigen::Matrix3d randomCovariance(std::mt19937& rng, double minStd, double maxStd)
{
  std::uniform_real_distribution<double> s(minStd, maxStd);
  const Eigen::Matrix3d r = randomRotation(rng);
  const Eigen::Vector3d sd(s(rng), s(rng), s(rng));
  return r * sd.cwiseProduct(sd).asDiagonal() * r.transpose();
}

inline SimilarityTransform randomSimilarity(
  std::mt19937& rng, double maxAngle, double maxTranslation, double maxLogScale)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector7d v;
  v[0] = maxLogScale * u(rng);
  v.segment<3>(1) = maxAngle * std::abs(u(rng)) * randomUnit(rng);
  v.tail<3>() = maxTranslation * Eigen::Vector3d(u(rng), u(rng), u(rng));
  return SimilarityTransform::exp(v);
}

} // namespace vimlop::fixtures

#endif
