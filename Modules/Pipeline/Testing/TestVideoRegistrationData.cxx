#include <vimlop/Pipeline/VideoRegistrationData.h>

#include <vimlop/Core/Error.h>

#include <gtest/gtest.h>

namespace vimlop
{
namespace
{

SfmReconstruction threeFramesTheMiddleUnregistered()
{
  SfmReconstruction sfm;
  sfm.frames.resize(3);
  for (int f = 0; f < 3; ++f)
  {
    sfm.frames[f].name = "frame" + std::to_string(f) + ".png";
    sfm.frames[f].registered = f != 1;
    sfm.frames[f].cameraToSfm.centre = Eigen::Vector3d(f, 0.0, 0.0);
    sfm.frames[f].intrinsics.fx = sfm.frames[f].intrinsics.fy = 200.0;
    sfm.frames[f].intrinsics.cx = 159.5;
    sfm.frames[f].intrinsics.cy = 119.5;
    sfm.frames[f].intrinsics.widthPx = 320;
    sfm.frames[f].intrinsics.heightPx = 240;
    sfm.frames[f].intrinsics.distortion = Eigen::VectorXd::Constant(5, 0.01);
  }
  SfmReconstruction::Point p;
  p.position = Eigen::Vector3d(1.0, 2.0, 3.0);
  p.covariance = Eigen::Vector3d(1.0, 4.0, 9.0).asDiagonal();
  sfm.points.push_back(p);
  return sfm;
}

TEST(VideoRegistrationData, KeepsRegisteredFramesWithTheirContoursAndScalesTheCovariances)
{
  const SfmReconstruction sfm = threeFramesTheMiddleUnregistered();
  std::vector<std::vector<ContourPoint>> contours(3);
  contours[2].push_back({ Eigen::Vector2d(10.0, 20.0), Eigen::Vector2d::UnitX() });
  std::vector<int> frameOf;
  const RegistrationData data = makeVideoRegistrationData(sfm, contours, 2.0, 0.1, &frameOf);
  ASSERT_EQ(data.frames.size(), 2u);
  EXPECT_EQ(frameOf, (std::vector<int>{ 0, 2 }));
  EXPECT_EQ(data.frames[1].frameId, 2);
  EXPECT_EQ(data.frames[1].contour.size(), 1u);
  // Frames were undistorted before SfM and contours: the data's cameras have no distortion.
  EXPECT_EQ(data.frames[0].intrinsics.distortion.size(), 0);
  ASSERT_EQ(data.pointCovariances.size(), 1u);
  // SfM units² to mm² at 2 mm per unit, plus the 0.1 mm floor.
  EXPECT_NEAR(data.pointCovariances[0](1, 1), 4.0 * 4.0 + 0.01, 1e-12);
  EXPECT_NEAR(data.pointCovariances[0](0, 1), 0.0, 1e-15);
  EXPECT_NO_THROW(data.validate());
}

TEST(VideoRegistrationData, ContourListsThatDoNotMatchTheFramesAreAnError)
{
  const SfmReconstruction sfm = threeFramesTheMiddleUnregistered();
  try
  {
    makeVideoRegistrationData(sfm, std::vector<std::vector<ContourPoint>>(2), 1.0, 0.1);
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "registration data: 2 contour lists for 3 SfM frames");
  }
}

TEST(VideoRegistrationData, FramesTakeTheIdsOfTheirFilesWhenGiven)
{
  // frame010.png, frame011.png (not registered), frame013.png.
  const SfmReconstruction sfm = threeFramesTheMiddleUnregistered();
  const std::vector<int> ids = { 10, 11, 13 };
  std::vector<int> frameOf;
  const RegistrationData data = makeVideoRegistrationData(
    sfm, std::vector<std::vector<ContourPoint>>(3), 1.0, 0.1, &frameOf, &ids);
  ASSERT_EQ(data.frames.size(), 2u);
  EXPECT_EQ(data.frames[0].frameId, 10);
  EXPECT_EQ(data.frames[1].frameId, 13);
  EXPECT_EQ(frameOf, (std::vector<int>{ 0, 2 })); // indices still
  const std::vector<int> twoIds = { 10, 11 };
  try
  {
    makeVideoRegistrationData(
      sfm, std::vector<std::vector<ContourPoint>>(3), 1.0, 0.1, nullptr, &twoIds);
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "registration data: 2 frame ids for 3 SfM frames");
  }
}

TEST(VideoRegistrationData, ANonPositiveScaleIsAnError)
{
  const SfmReconstruction sfm = threeFramesTheMiddleUnregistered();
  EXPECT_THROW(
    makeVideoRegistrationData(sfm, std::vector<std::vector<ContourPoint>>(3), 0.0, 0.1), Error);
  EXPECT_THROW(
    makeVideoRegistrationData(sfm, std::vector<std::vector<ContourPoint>>(3), 1.0, -1.0), Error);
}

} // namespace
} // namespace vimlop
