#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

using namespace vimlop;

TEST(CameraPose, WorldCameraRoundTrip)
{
  CameraPose pose;
  pose.rotation = rotationFromVector(Eigen::Vector3d(0.2, -0.4, 1.0));
  pose.centre = Eigen::Vector3d(10.0, -5.0, 3.0);
  const Eigen::Vector3d y(1.0, 2.0, 3.0);
  EXPECT_LT((pose.cameraToWorld(pose.worldToCamera(y)) - y).norm(), 1e-12);
  // The centre is the camera origin.
  EXPECT_LT(pose.worldToCamera(pose.centre).norm(), 1e-12);
  const Eigen::Vector4d h = pose.matrix() * Eigen::Vector3d(0.5, 0.5, 2.0).homogeneous();
  EXPECT_LT((h.head<3>() - pose.cameraToWorld({ 0.5, 0.5, 2.0 })).norm(), 1e-12);
}

TEST(CameraPose, LookAtPointsTheOpticalAxisAndImageUp)
{
  const CameraPose pose = CameraPose::lookAt({ 0, 0, 0 }, { 0, 10, 0 }, { 0, 0, 1 });
  EXPECT_TRUE(isRotation(pose.rotation, 1e-12));
  EXPECT_LT((pose.viewDirection() - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  // Image y points down, so world up (+z) is camera -y.
  EXPECT_LT((pose.rotation.col(1) + Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  // The target lies on the optical axis, in front of the camera.
  const Eigen::Vector3d target = pose.worldToCamera({ 0, 10, 0 });
  EXPECT_NEAR(target.z(), 10.0, 1e-12);
  EXPECT_LT(target.head<2>().norm(), 1e-12);
}

TEST(CameraPose, LookAtRejectsDegenerateInput)
{
  EXPECT_THROW(CameraPose::lookAt({ 1, 1, 1 }, { 1, 1, 1 }, { 0, 0, 1 }), Error);
  EXPECT_THROW(CameraPose::lookAt({ 0, 0, 0 }, { 0, 0, 5 }, { 0, 0, 1 }), Error);
}

TEST(CameraPose, FromMatrixValidates)
{
  const CameraPose pose = CameraPose::lookAt({ 1, 2, 3 }, { 3, 2, 1 }, { 0, 1, 0 });
  const CameraPose back = CameraPose::fromMatrix(pose.matrix());
  EXPECT_LT((back.matrix() - pose.matrix()).norm(), 1e-12);
  Eigen::Matrix4d scaled = pose.matrix();
  scaled.topLeftCorner<3, 3>() *= 2.0;
  try
  {
    CameraPose::fromMatrix(scaled);
    FAIL() << "a scaled rotation was accepted";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "camera pose matrix: upper-left 3x3 block is not a rotation");
  }
  Eigen::Matrix4d nan = pose.matrix();
  nan(0, 3) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(CameraPose::fromMatrix(nan), Error);
}
