#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/SimilarityTransform.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <random>

using namespace vimlop;

namespace
{

SimilarityTransform randomTransform(std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector7d v;
  v << 0.5 * u(rng), u(rng), u(rng), u(rng), 30 * u(rng), 30 * u(rng), 30 * u(rng);
  return SimilarityTransform::exp(v);
}

} // namespace

TEST(SimilarityTransform, ApplyMatchesMatrix)
{
  std::mt19937 rng(1);
  const SimilarityTransform t = randomTransform(rng);
  const Eigen::Vector3d x(1.0, -2.0, 3.5);
  const Eigen::Vector4d h = t.matrix() * x.homogeneous();
  EXPECT_LT((t.apply(x) - h.head<3>()).norm(), 1e-12);
  EXPECT_LT((t.apply(x) - (t.scale * t.rotation * x + t.translation)).norm(), 1e-12);
}

TEST(SimilarityTransform, ComposeAppliesFirstThenSecond)
{
  std::mt19937 rng(2);
  const SimilarityTransform a = randomTransform(rng);
  const SimilarityTransform b = randomTransform(rng);
  const Eigen::Vector3d x(4.0, 0.5, -1.0);
  EXPECT_LT((b.compose(a).apply(x) - b.apply(a.apply(x))).norm(), 1e-10);
  EXPECT_LT((b.compose(a).matrix() - b.matrix() * a.matrix()).norm(), 1e-10);
}

TEST(SimilarityTransform, InverseUndoes)
{
  std::mt19937 rng(3);
  for (int i = 0; i < 20; ++i)
  {
    const SimilarityTransform t = randomTransform(rng);
    const Eigen::Vector3d x(-3.0, 7.0, 2.0);
    EXPECT_LT((t.inverse().apply(t.apply(x)) - x).norm(), 1e-10);
    EXPECT_LT((t.compose(t.inverse()).matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-10);
  }
}

TEST(SimilarityTransform, ExpLogRoundTrip)
{
  std::mt19937 rng(4);
  for (int i = 0; i < 50; ++i)
  {
    const SimilarityTransform t = randomTransform(rng);
    const SimilarityTransform back = SimilarityTransform::exp(t.log());
    EXPECT_NEAR(back.scale, t.scale, 1e-12);
    EXPECT_LT((back.rotation - t.rotation).norm(), 1e-10);
    EXPECT_LT((back.translation - t.translation).norm(), 1e-12);
  }
  Vector7d v;
  v << std::log(2.0), 0.0, 0.0, M_PI / 2, 1.0, 2.0, 3.0;
  const SimilarityTransform t = SimilarityTransform::exp(v);
  EXPECT_NEAR(t.scale, 2.0, 1e-15);
  // A quarter turn about z takes x to y.
  EXPECT_LT((t.rotation * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  EXPECT_LT((t.log() - v).norm(), 1e-12);
}

TEST(SimilarityTransform, MovesCamerasConsistently)
{
  std::mt19937 rng(5);
  const SimilarityTransform t = randomTransform(rng);
  const CameraPose pose = CameraPose::lookAt({ 1, 2, 3 }, { 4, 4, 9 }, { 0, 0, 1 });
  const CameraPose moved = t.apply(pose);
  EXPECT_LT((moved.centre - t.apply(pose.centre)).norm(), 1e-12);
  // A point seen by the camera is seen in the same direction, s times farther.
  const Eigen::Vector3d x(5.0, 3.0, 8.0);
  EXPECT_LT((moved.worldToCamera(t.apply(x)) - t.scale * pose.worldToCamera(x)).norm(), 1e-9);
}

TEST(SimilarityTransform, FromMatrixRoundTripAndErrors)
{
  std::mt19937 rng(6);
  const SimilarityTransform t = randomTransform(rng);
  const SimilarityTransform back = SimilarityTransform::fromMatrix(t.matrix());
  EXPECT_NEAR(back.scale, t.scale, 1e-12);
  EXPECT_LT((back.translation - t.translation).norm(), 1e-12);

  Eigen::Matrix4d mirror = Eigen::Matrix4d::Identity();
  mirror(0, 0) = -1.0;
  EXPECT_THROW(
    {
      try
      {
        SimilarityTransform::fromMatrix(mirror);
      }
      catch (const Error& e)
      {
        EXPECT_STREQ(
          e.what(), "similarity matrix: upper-left 3x3 block has non-positive determinant");
        throw;
      }
    },
    Error);
  Eigen::Matrix4d shear = Eigen::Matrix4d::Identity();
  shear(0, 1) = 0.5;
  EXPECT_THROW(SimilarityTransform::fromMatrix(shear), Error);
  Eigen::Matrix4d projective = Eigen::Matrix4d::Identity();
  projective(3, 0) = 0.1;
  EXPECT_THROW(SimilarityTransform::fromMatrix(projective), Error);
  EXPECT_FALSE(SimilarityTransform{ -1.0 }.isValid());
  EXPECT_TRUE(t.isValid());
}
