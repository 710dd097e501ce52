#include <vimlop/Core/CanonicalStarts.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>

#include <gtest/gtest.h>

namespace vimlop
{
namespace
{

TEST(CanonicalStarts, PutTheMiddleFrameAtEveryPoseAtTheGivenScale)
{
  RegistrationData data;
  for (int f = 0; f < 5; ++f)
  {
    VideoFrame frame;
    frame.frameId = 10 + f;
    frame.cameraToSfm.centre = Eigen::Vector3d(0.1 * f, 0.0, 0.0);
    frame.cameraToSfm.rotation = rotationFromVector(Eigen::Vector3d(0.0, 0.05 * f, 0.0));
    data.frames.push_back(frame);
  }
  std::vector<CameraPose> poses(2);
  poses[0].centre = Eigen::Vector3d(10.0, 20.0, 30.0);
  poses[1].centre = Eigen::Vector3d(-5.0, 0.0, 2.0);
  poses[1].rotation = rotationFromVector(Eigen::Vector3d(0.3, -0.2, 0.1));
  int anchor = -1;
  const std::vector<SimilarityTransform> starts = canonicalStarts(data, 4.0, poses, &anchor);
  EXPECT_EQ(anchor, 12);
  ASSERT_EQ(starts.size(), 2u);
  for (size_t i = 0; i < starts.size(); ++i)
  {
    const CameraPose placed = starts[i].apply(data.frames[2].cameraToSfm);
    EXPECT_NEAR((placed.centre - poses[i].centre).norm(), 0.0, 1e-9);
    EXPECT_NEAR((placed.rotation - poses[i].rotation).norm(), 0.0, 1e-9);
    EXPECT_DOUBLE_EQ(starts[i].scale, 4.0);
  }
}

TEST(CanonicalStarts, ATrackedRotationTurnsEveryCanonicalPositionOnce)
{
  // Two positions, the first with two views and a roll: three poses, two places.
  std::vector<CameraPose> canonical(3);
  canonical[0].centre = Eigen::Vector3d(1.0, 2.0, 3.0);
  canonical[1].centre = Eigen::Vector3d(1.2, 2.0, 3.0);
  canonical[1].rotation = rotationFromVector(Eigen::Vector3d(0.0, 0.0, 2.0));
  canonical[2].centre = Eigen::Vector3d(-4.0, 0.0, 3.0);
  canonical[2].rotation = rotationFromVector(Eigen::Vector3d(0.5, 0.0, 0.0));
  CameraPose tracked;
  tracked.centre = Eigen::Vector3d(0.0, 1.0, 3.0);
  tracked.rotation = rotationFromVector(Eigen::Vector3d(0.1, -0.4, 2.8));
  const std::vector<CameraPose> poses = turnedAsTracked(canonical, tracked);
  ASSERT_EQ(poses.size(), 3u) << "the tracked pose, then the two places";
  EXPECT_EQ(poses[0].centre, tracked.centre);
  EXPECT_EQ(poses[1].centre, canonical[0].centre);
  EXPECT_EQ(poses[2].centre, canonical[2].centre);
  for (const CameraPose& p : poses)
  {
    EXPECT_EQ(p.rotation, tracked.rotation);
  }
  EXPECT_EQ(turnedAsTracked(canonical, tracked, 0.1).size(), 4u) << "0.2 mm apart: two places";
}

TEST(CanonicalStarts, DataWithoutFramesAreAnError)
{
  try
  {
    canonicalStarts(RegistrationData(), 1.0, std::vector<CameraPose>(1));
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "canonical starts: no registered frame");
  }
}

} // namespace
} // namespace vimlop
