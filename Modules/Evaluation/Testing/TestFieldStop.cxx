#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/FieldStop.h>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <cmath>

#include <string>

using namespace vimlop;

TEST(FieldStop, IsOffByDefaultAndThenChangesNoPixel)
{
  const FieldStopOptions off;
  EXPECT_TRUE(off.isOff());
  const cv::Mat gain = fieldStopGain(off, 32, 24);
  ASSERT_EQ(gain.type(), CV_32F);
  EXPECT_EQ(cv::countNonZero(gain != 1.0f), 0);
}

TEST(FieldStop, BlackensEveryPixelOutsideTheCircleAndLeavesTheInsideWhole)
{
  // 320 x 240: the half-diagonal is 200 px, so the fraction 0.6 gives a
  // circle of radius 120 px, as tall as the image; centred on pixel (160, 120).
  FieldStopOptions o;
  o.radiusFraction = 0.6;
  o.centreOffsetPx = Eigen::Vector2d(0.5, 0.5);
  o.edgeSoftnessPx = 2.0;
  EXPECT_DOUBLE_EQ(o.radiusFor(320, 240), 120.0);
  const cv::Mat gain = fieldStopGain(o, 320, 240);
  for (int v = 0; v < 240; ++v)
  {
    for (int u = 0; u < 320; ++u)
    {
      const double r = std::hypot(u - 160.0, v - 120.0);
      if (r >= 121.0)
      {
        ASSERT_EQ(gain.at<float>(v, u), 0.0f) << u << ", " << v;
      }
      else if (r <= 119.0)
      {
        ASSERT_EQ(gain.at<float>(v, u), 1.0f) << u << ", " << v;
      }
    }
  }
  // The soft edge is half way at the radius.
  EXPECT_NEAR(gain.at<float>(120, 280), 0.5f, 1e-6f);
  // The same circle given in pixels, moved 10 px right.
  FieldStopOptions px;
  px.radiusPx = 120.0;
  px.centreOffsetPx = Eigen::Vector2d(10.5, 0.5);
  px.edgeSoftnessPx = 0.0;
  const cv::Mat moved = fieldStopGain(px, 320, 240);
  EXPECT_EQ(moved.at<float>(120, 45), 0.0f);
  EXPECT_EQ(moved.at<float>(120, 290), 1.0f);
}

TEST(FieldStop, VignettingDarkensTheEdgeRelativeToTheCentreByItsStrength)
{
  FieldStopOptions o;
  o.radiusPx = 100.0;
  o.centreOffsetPx = Eigen::Vector2d(0.5, 0.5); // centre on pixel (160, 120)
  o.edgeSoftnessPx = 0.0;
  o.vignettingStrength = 0.4;
  const cv::Mat gain = fieldStopGain(o, 320, 240);
  EXPECT_FLOAT_EQ(gain.at<float>(120, 160), 1.0f);
  EXPECT_FLOAT_EQ(gain.at<float>(120, 260), 0.6f); // on the circle: 1 - 0.4
  EXPECT_FLOAT_EQ(gain.at<float>(120, 210), 0.9f); // half way: 1 - 0.4 / 4
  EXPECT_EQ(gain.at<float>(120, 261), 0.0f);

  // Without a circle, the strength is the loss at the image's corner.
  FieldStopOptions open;
  open.vignettingStrength = 0.5;
  open.centreOffsetPx = Eigen::Vector2d(0.5, 0.5);
  EXPECT_FALSE(open.isOff());
  // 321 x 241 centred on (160.5, 120.5): pixel (0, 0) is the half-diagonal
  // hypot(321, 241) / 2 from the centre.
  const cv::Mat corner = fieldStopGain(open, 321, 241);
  EXPECT_NEAR(corner.at<float>(0, 0), 0.5f, 1e-6f);
  EXPECT_FLOAT_EQ(corner.at<float>(120, 160),
    1.0f -
      0.5f *
        static_cast<float>(std::pow(std::hypot(0.5, 0.5) / (0.5 * std::hypot(321.0, 241.0)), 2)));
}

TEST(FieldStop, RefusesTwoRadiiAVignettingOutsideZeroToOneAndNegativeSizes)
{
  auto message = [](const FieldStopOptions& o)
  {
    try
    {
      o.validate();
    }
    catch (const Error& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  FieldStopOptions both;
  both.radiusFraction = 0.6;
  both.radiusPx = 100.0;
  EXPECT_EQ(message(both),
    "give the field stop's radius either as a fraction of the half-diagonal or in pixels, not "
    "both");
  FieldStopOptions bright;
  bright.vignettingStrength = 1.5;
  EXPECT_EQ(message(bright), "the vignetting strength must lie in [0, 1], not 1.5");
  FieldStopOptions negative;
  negative.edgeSoftnessPx = -1.0;
  EXPECT_EQ(
    message(negative), "the field stop's edge softness must be a finite number >= 0, not -1");
  EXPECT_THROW(fieldStopGain(bright, 8, 8), Error);
}
