#include <vimlop/Core/Error.h>
#include <vimlop/Video/OccludingContourDetector.h>

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <functional>

using namespace vimlop;

namespace
{

constexpr int Width = 160;
constexpr int Height = 120;

/// An 8-bit BGR picture of a scene given by its intensity at any point,
/// averaged over 8 x 8 samples per pixel (pixel centres at integers), with a
/// little blur like a lens.
cv::Mat picture(const std::function<cv::Vec3d(double, double)>& intensity)
{
  cv::Mat image(Height, Width, CV_64FC3);
  for (int v = 0; v < Height; ++v)
  {
    for (int u = 0; u < Width; ++u)
    {
      cv::Vec3d sum(0, 0, 0);
      for (int j = 0; j < 8; ++j)
      {
        for (int i = 0; i < 8; ++i)
        {
          sum += intensity(u - 0.5 + (i + 0.5) / 8.0, v - 0.5 + (j + 0.5) / 8.0);
        }
      }
      image.at<cv::Vec3d>(v, u) = sum / 64.0;
    }
  }
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.6);
  cv::Mat out;
  image.convertTo(out, CV_8UC3);
  return out;
}

cv::Vec3d grey(double value)
{
  return { value, value, value };
}

const Eigen::Vector2d DiscCentre(80.3, 60.7);
constexpr double DiscRadius = 30.0;

bool inDisc(double u, double v)
{
  return (Eigen::Vector2d(u, v) - DiscCentre).norm() < DiscRadius;
}

ContourDetectionOptions dense()
{
  ContourDetectionOptions o;
  o.spacingPx = 0.0;
  return o;
}

std::string messageOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(OccludingContourDetector, FindsTheSilhouetteOfANearBrightDiscWithOutwardNormals)
{
  // A near fold (bright, the light is at the camera) in front of a far wall.
  const cv::Mat frame =
    picture([](double u, double v) { return grey(inDisc(u, v) ? 170.0 : 70.0); });
  const std::vector<ContourPoint> points = OccludingContourDetector(dense()).detect(frame);
  ASSERT_GT(points.size(), 150u); // the circumference is 188 px
  for (const ContourPoint& p : points)
  {
    const Eigen::Vector2d radial = p.pixel - DiscCentre;
    EXPECT_NEAR(radial.norm(), DiscRadius, 0.5);
    EXPECT_NEAR(p.normal.norm(), 1.0, 1e-9);
    // From the near, occluding disc to the far side: outwards.
    EXPECT_GT(p.normal.dot(radial.normalized()), std::cos(10.0 * M_PI / 180.0));
  }
}

TEST(OccludingContourDetector, NormalsOfAFarDarkHolePointIntoIt)
{
  // Looking down a passage: the dark, far opening is surrounded by near wall.
  const cv::Mat frame =
    picture([](double u, double v) { return grey(inDisc(u, v) ? 50.0 : 150.0); });
  const std::vector<ContourPoint> points = OccludingContourDetector(dense()).detect(frame);
  ASSERT_GT(points.size(), 150u);
  for (const ContourPoint& p : points)
  {
    const Eigen::Vector2d radial = p.pixel - DiscCentre;
    EXPECT_NEAR(radial.norm(), DiscRadius, 0.5);
    EXPECT_LT(p.normal.dot(radial.normalized()), -std::cos(10.0 * M_PI / 180.0));
  }
}

TEST(OccludingContourDetector, DarkSideTestSuppressesVessels)
{
  // A dark vessel 4 px wide across bright mucosa: dark on one side of each
  // edge only across the vessel's width.
  const cv::Mat frame =
    picture([](double u, double) { return grey(std::abs(u - 80.2) < 2.0 ? 70.0 : 160.0); });
  EXPECT_TRUE(OccludingContourDetector(dense()).detect(frame).empty());
  ContourDetectionOptions noDarkSideTest = dense();
  noDarkSideTest.darkSideProbesPx.clear();
  EXPECT_GT(OccludingContourDetector(noDarkSideTest).detect(frame).size(), 100u);
}

TEST(OccludingContourDetector, ScaleTestSuppressesGradualShading)
{
  // The same fall in brightness as a contour's, but spread over 10 pixels.
  auto ramp = [](double u, double)
  { return grey(160.0 - 100.0 * std::clamp((u - 75.0) / 10.0, 0.0, 1.0)); };
  const cv::Mat frame = picture(ramp);
  EXPECT_TRUE(OccludingContourDetector(dense()).detect(frame).empty());
  ContourDetectionOptions noScaleTest = dense();
  noScaleTest.minScaleRatio = 0.0;
  EXPECT_GT(OccludingContourDetector(noScaleTest).detect(frame).size(), 100u);
  // A step of that height is kept.
  const cv::Mat step = picture([](double u, double) { return grey(u < 80.0 ? 160.0 : 60.0); });
  EXPECT_GT(OccludingContourDetector(dense()).detect(step).size(), 100u);
}

TEST(OccludingContourDetector, RedChannelIgnoresBloodTexture)
{
  // An edge in green and blue only (as haemoglobin makes) is texture.
  const cv::Mat frame = picture(
    [](double u, double)
    {
      return u < 80.0 ? cv::Vec3d(60, 60, 180) : cv::Vec3d(140, 140, 180); // BGR
    });
  EXPECT_TRUE(OccludingContourDetector(dense()).detect(frame).empty());
  ContourDetectionOptions luminance = dense();
  luminance.channel = ContourChannel::Luminance;
  EXPECT_GT(OccludingContourDetector(luminance).detect(frame).size(), 100u);
}

TEST(OccludingContourDetector, ThinsPointsToTheSpacing)
{
  const cv::Mat frame =
    picture([](double u, double v) { return grey(inDisc(u, v) ? 170.0 : 70.0); });
  ContourDetectionOptions o;
  o.spacingPx = 3.0;
  const std::vector<ContourPoint> points = OccludingContourDetector(o).detect(frame);
  for (size_t i = 0; i < points.size(); ++i)
  {
    for (size_t j = i + 1; j < points.size(); ++j)
    {
      ASSERT_GE((points[i].pixel - points[j].pixel).norm(), 3.0);
    }
  }
  // Greedy thinning leaves gaps of 3 to 6 px along the 188 px circumference.
  const double circumference = 2.0 * M_PI * DiscRadius;
  EXPECT_GE(static_cast<double>(points.size()), circumference / 6.0);
  EXPECT_LE(static_cast<double>(points.size()), circumference / 3.0 + 1.0);
}

TEST(OccludingContourDetector, RejectsBadFramesAndOptions)
{
  const OccludingContourDetector detector;
  EXPECT_EQ(messageOf([&] { detector.detect(cv::Mat()); }), "contour detector: the frame is empty");
  EXPECT_EQ(messageOf([&] { detector.detect(cv::Mat(10, 10, CV_16UC3)); }),
    "contour detector: expected an 8-bit grey or BGR frame");
  ContourDetectionOptions o;
  o.highThreshold = 0.5 * o.lowThreshold;
  EXPECT_NE(
    messageOf([&] { OccludingContourDetector bad(o); }).find("high threshold at least the low one"),
    std::string::npos);
}
