#include "ErrorMessage.h"
#include <vimlop/Core/FramePose.h>

#include <gtest/gtest.h>

#include <limits>

using namespace vimlop;

namespace
{

FramePose poseAt(int frameId, const Eigen::Vector3d& centre)
{
  FramePose pose;
  pose.frameId = frameId;
  pose.cameraToWorld.centre = centre;
  return pose;
}

} // namespace

TEST(FramePose, PosesWithDistinctIdsInsideACTPass)
{
  EXPECT_NO_THROW(checkFramePoses({}));
  EXPECT_NO_THROW(checkFramePoses({ poseAt(0, { 120.0, 100.0, 20.0 }),
    poseAt(7, { -300.0, 0.0, 900.0 }), poseAt(2, { 0.0, 0.0, 0.0 }) }));
}

TEST(FramePose, ARepeatedIdAFarCameraAndANonFiniteOneAreNamedByTheirIndex)
{
  EXPECT_EQ(fixtures::errorMessageOf(
              []
              {
                checkFramePoses({ poseAt(3, Eigen::Vector3d::Zero()),
                  poseAt(7, Eigen::Vector3d::Zero()), poseAt(3, Eigen::Vector3d::Ones()) });
              }),
    "pose 2: frame id 3 repeats pose 0's");
  EXPECT_EQ(
    fixtures::errorMessageOf(
      [] {
        checkFramePoses({ poseAt(0, Eigen::Vector3d::Zero()), poseAt(1, { 1e39, 0.0, 0.0 }) });
      }),
    "pose 1: the camera of frame 1 lies 1e+39 mm from the origin, farther than 1 km: not a pose "
    "in a CT");
  EXPECT_EQ(
    fixtures::errorMessageOf(
      [] {
        checkFramePoses({ poseAt(4, { std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0 }) });
      }),
    "pose 0: the camera of frame 4 is not finite");
}
