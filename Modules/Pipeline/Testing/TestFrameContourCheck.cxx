#include <vimlop/Pipeline/FrameContourCheck.h>

#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include "ErrorMessage.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vimlop
{
namespace
{

TEST(FrameContourCheck, RefusesAMaskOrAFrameOfAnotherSize)
{
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeTube(4.0, 60.0, 0.35));
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] { FrameContourCheck(model, k, cv::Mat(120, 160, CV_8U, cv::Scalar(255))); }),
    "contour check: a field-of-view mask of 160 x 120 pixels, but the camera is 320 x 240");
  const FrameContourCheck check(model, k, cv::Mat());
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] { check.check(cv::Mat(480, 640, CV_8UC3), fixtures::cameraOnTheTubeAxis()); }),
    "contour check: a frame of 640 x 480 pixels, but the camera is 320 x 240");
}

TEST(FrameContourCheck, AFrameWithoutEdgesMatchesNothingButStillGivesTheModelContours)
{
  // A flat frame (the lens against the wall) has no contour to check the
  // pose with: no error, rather than a small one.
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeTube(4.0, 60.0, 0.35));
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  const FrameContourCheck check(model, k, cv::Mat());
  const FrameContourAgreement a =
    check.check(cv::Mat(k.heightPx, k.widthPx, CV_8UC3, cv::Scalar(90, 90, 160)),
      fixtures::cameraOnTheTubeAxis());
  EXPECT_EQ(a.detected, 0);
  EXPECT_EQ(a.matched, 0);
  EXPECT_TRUE(std::isnan(a.medianErrorPx));
  EXPECT_GT(a.modelContours.size(), 50u);
}

} // namespace
} // namespace vimlop
