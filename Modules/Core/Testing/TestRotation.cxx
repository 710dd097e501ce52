#include <vimlop/Core/Rotation.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <random>

using namespace vimlop;

TEST(Rotation, SkewIsCrossProduct)
{
  const Eigen::Vector3d a(0.3, -1.2, 2.0);
  const Eigen::Vector3d b(-0.7, 0.4, 1.1);
  EXPECT_LT((skew(a) * b - a.cross(b)).norm(), 1e-15);
}

TEST(Rotation, VectorRoundTripMatchesEigenAngleAxis)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i)
  {
    Eigen::Vector3d w(u(rng), u(rng), u(rng));
    w *= (M_PI - 1e-6) * std::abs(u(rng)) / w.norm();
    const Eigen::Matrix3d r = rotationFromVector(w);
    const Eigen::Matrix3d reference =
      Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
    EXPECT_LT((r - reference).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((rotationToVector(r) - w).norm(), 1e-8);
    EXPECT_TRUE(isRotation(r));
  }
}

TEST(Rotation, TinyAnglesStayExact)
{
  const Eigen::Vector3d w(1e-9, -2e-9, 3e-9);
  const Eigen::Matrix3d r = rotationFromVector(w);
  EXPECT_LT(((r - Eigen::Matrix3d::Identity()) - skew(w)).norm(), 1e-17);
  EXPECT_LT((rotationToVector(r) - w).norm(), 1e-15);
}

TEST(Rotation, AngleBetween)
{
  const Eigen::Matrix3d a = rotationFromVector(Eigen::Vector3d(0.1, 0.2, -0.3));
  const Eigen::Matrix3d b = a * rotationFromVector(Eigen::Vector3d(0.0, 0.25, 0.0));
  EXPECT_NEAR(rotationAngleBetween(a, b), 0.25, 1e-12);
}

TEST(Rotation, RejectsReflectionsAndScaledMatrices)
{
  Eigen::Matrix3d reflection = Eigen::Matrix3d::Identity();
  reflection(0, 0) = -1.0;
  EXPECT_FALSE(isRotation(reflection));
  EXPECT_FALSE(isRotation(2.0 * Eigen::Matrix3d::Identity()));
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(isRotation(nan));
}

TEST(Rotation, NearestRotationRemovesNoise)
{
  const Eigen::Matrix3d r = rotationFromVector(Eigen::Vector3d(0.4, -0.1, 0.7));
  Eigen::Matrix3d noisy = r;
  noisy(0, 1) += 1e-3;
  noisy(2, 2) -= 2e-3;
  const Eigen::Matrix3d fixed = nearestRotation(noisy);
  EXPECT_TRUE(isRotation(fixed, 1e-12));
  EXPECT_LT(rotationAngleBetween(fixed, r), 3e-3);
  // A reflection is mapped to a proper rotation, never to itself.
  EXPECT_TRUE(isRotation(nearestRotation(-Eigen::Matrix3d::Identity()), 1e-12));
}

TEST(Rotation, TowardsTurnsAFractionOfTheWayAlongTheShorterArc)
{
  // Eigen's quaternion slerp is the reference: the same arc, the same point on it.
  const Eigen::Matrix3d from =
    Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 0).normalized()).toRotationMatrix();
  const Eigen::Matrix3d to =
    Eigen::AngleAxisd(-1.1, Eigen::Vector3d(0, 1, 3).normalized()).toRotationMatrix();
  for (const double fraction : { 0.0, 0.1, 0.5, 1.0 })
  {
    const Eigen::Matrix3d reference =
      Eigen::Quaterniond(from).slerp(fraction, Eigen::Quaterniond(to)).toRotationMatrix();
    EXPECT_LT((rotationTowards(from, to, fraction) - reference).cwiseAbs().maxCoeff(), 1e-12)
      << fraction;
  }
}
