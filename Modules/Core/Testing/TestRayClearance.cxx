#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/RayClearance.h>

#include <gtest/gtest.h>

using namespace vimlop;

TEST(RayClearance, FreeLengthIsTheLastFreeStepBeforeTheWall)
{
  // A box cavity; its wall is 9.7 mm from (0.3, 0, 0) along +x.
  const MeshTree tree(fixtures::makeBox({ -10, -10, -10 }, { 10, 10, 10 }));
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
  EXPECT_DOUBLE_EQ(freeLengthAlongRay(tree, Eigen::Vector3d(0.3, 0, 0), x, 40.0, 1.0), 9.0);
  EXPECT_DOUBLE_EQ(freeLengthAlongRay(tree, Eigen::Vector3d(0.3, 0, 0), x, 40.0, 0.5), 9.5);
  EXPECT_DOUBLE_EQ(freeLengthAlongRay(tree, Eigen::Vector3d(2.2, 0, 0), x, 40.0, 3.0), 6.0);
}

TEST(RayClearance, AFreeRayReturnsTheLimit)
{
  const MeshTree tree(fixtures::makeBox({ -10, -10, -10 }, { 10, 10, 10 }));
  EXPECT_DOUBLE_EQ(
    freeLengthAlongRay(tree, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY(), 8.0, 1.0), 8.0);
  // One step of the whole length asks only whether the segment is free.
  EXPECT_DOUBLE_EQ(
    freeLengthAlongRay(tree, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY(), 8.0, 8.0), 8.0);
  EXPECT_DOUBLE_EQ(
    freeLengthAlongRay(tree, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY(), 12.0, 12.0), 0.0);
  EXPECT_DOUBLE_EQ(
    freeLengthAlongRay(tree, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY(), 0.0, 1.0), 0.0);
}

TEST(RayClearance, BadStepOrLimitGetsAClearError)
{
  const MeshTree tree(fixtures::makeBox({ -10, -10, -10 }, { 10, 10, 10 }));
  const std::string message = "ray clearance: the step must be positive and the limit not negative";
  for (const auto& [limit, step] : { std::pair(10.0, 0.0), std::pair(10.0, -1.0),
         std::pair(-1.0, 1.0), std::pair(10.0, std::nan("")) })
  {
    try
    {
      freeLengthAlongRay(tree, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), limit, step);
      ADD_FAILURE() << "no error for limit " << limit << ", step " << step;
    }
    catch (const Error& e)
    {
      EXPECT_EQ(std::string(e.what()), message);
    }
  }
}
