#include "ErrorMessage.h"
#include <vimlop/Server/PoseStreamServer.h>

#include <gtest/gtest.h>

#include <limits>

using namespace vimlop;

namespace
{

PoseStreamServerOptions anyFreePort()
{
  PoseStreamServerOptions options;
  options.port = 0;
  return options;
}

std::vector<FramePose> twoPoses()
{
  std::vector<FramePose> poses(2);
  poses[0].frameId = 0;
  poses[1].frameId = 1;
  poses[1].cameraToWorld.centre = Eigen::Vector3d(120.0, 100.0, 20.0);
  return poses;
}

} // namespace

TEST(PoseStreamServer, PublishesPosesInsideACT)
{
  PoseStreamServer server(anyFreePort());
  EXPECT_GT(server.port(), 0);
  SimilarityTransform ctFromSfm;
  ctFromSfm.scale = 0.5;
  EXPECT_NO_THROW(server.publish(&ctFromSfm, twoPoses()));
  EXPECT_NO_THROW(server.publish(nullptr, {}));
}

TEST(PoseStreamServer, RefusesToPublishARepeatedIdOrAPoseBeyondFloats)
{
  PoseStreamServer server(anyFreePort());
  std::vector<FramePose> poses = twoPoses();
  poses[1].frameId = 0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(nullptr, poses); }),
    "pose server: refusing to publish: pose 1: frame id 0 repeats pose 0's");
  poses = twoPoses();
  poses[0].cameraToWorld.centre.z() = 4e38; // -inf as the protocol's float
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(nullptr, poses); }),
    "pose server: refusing to publish: pose 0: the camera of frame 0 lies 4e+38 mm from the "
    "origin, farther than 1 km: not a pose in a CT");
  SimilarityTransform ctFromSfm;
  ctFromSfm.translation.x() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(&ctFromSfm, twoPoses()); }),
    "pose server: refusing to publish: CTFromSfM is not a finite similarity within 1 km of the "
    "CT origin");
}
