#include <vimlop/Rendering/MucosaTexture.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>

using namespace vimlop;

namespace
{

std::vector<Eigen::Vector3d> samplePoints(int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i)
  {
    points.emplace_back(u(rng), u(rng), u(rng));
  }
  return points;
}

} // namespace

TEST(MucosaTexture, IsReproducibleAndDependsOnTheSeed)
{
  MucosaTextureOptions o;
  o.seed = 7;
  const MucosaTexture a(o);
  const MucosaTexture b(o);
  o.seed = 8;
  const MucosaTexture c(o);
  int different = 0;
  for (const Eigen::Vector3d& p : samplePoints(200, 1))
  {
    EXPECT_EQ(a.albedo(p), b.albedo(p));
    different += (a.albedo(p) - c.albedo(p)).norm() > 1e-3;
  }
  EXPECT_GT(different, 150);
}

TEST(MucosaTexture, AlbedoIsAPinkRedInRange)
{
  const MucosaTexture texture;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  const std::vector<Eigen::Vector3d> points = samplePoints(5000, 2);
  for (const Eigen::Vector3d& p : points)
  {
    const Eigen::Vector3d a = texture.albedo(p);
    ASSERT_GE(a.minCoeff(), 0.0);
    ASSERT_LE(a.maxCoeff(), 1.0);
    mean += a / points.size();
  }
  // Red dominates, as in mucosa.
  EXPECT_GT(mean.x(), 1.5 * mean.y());
  EXPECT_GT(mean.x(), 1.5 * mean.z());
  EXPECT_NEAR(mean.x(), texture.options().baseColour.x(), 0.1);
}

TEST(MucosaTexture, BloodTextureIsStrongInGreenAndFaintInRed)
{
  // The contour detector relies on this (ContourChannel::Red): the log
  // albedo varies several times more in green than in red.
  const MucosaTexture texture;
  std::vector<double> red;
  std::vector<double> green;
  for (const Eigen::Vector3d& p : samplePoints(5000, 3))
  {
    const Eigen::Vector3d a = texture.albedo(p);
    red.push_back(std::log(a.x()));
    green.push_back(std::log(a.y()));
  }
  auto stddev = [](const std::vector<double>& v)
  {
    double mean = 0.0;
    for (double x : v)
    {
      mean += x / v.size();
    }
    double var = 0.0;
    for (double x : v)
    {
      var += (x - mean) * (x - mean) / v.size();
    }
    return std::sqrt(var);
  };
  EXPECT_GT(stddev(green), 2.0 * stddev(red));
}

TEST(MucosaTexture, NoiseIsSmoothAndVanishesOnTheLattice)
{
  const MucosaTexture texture;
  for (const Eigen::Vector3d& p : samplePoints(200, 4))
  {
    const Eigen::Vector3d lattice(std::floor(p.x()), std::floor(p.y()), std::floor(p.z()));
    EXPECT_NEAR(texture.noise(lattice, 0), 0.0, 1e-12);
    const double n = texture.noise(p, 0);
    EXPECT_LE(std::abs(n), 1.0);
    // Lipschitz: a step of 0.001 lattice units changes it by little.
    EXPECT_LT(std::abs(texture.noise(p + Eigen::Vector3d(1e-3, 0, 0), 0) - n), 5e-3);
  }
}
