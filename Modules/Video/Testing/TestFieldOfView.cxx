#include <vimlop/Core/Error.h>
#include <vimlop/Video/FieldOfView.h>
#include <vimlop/Video/OccludingContourDetector.h>

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>
#include <functional>
#include <random>
#include <string>

using namespace vimlop;

namespace
{

constexpr int Width = 320;
constexpr int Height = 240;

/// Frames of a moving texture (bright blobs on a mid-grey, shifted a few
/// pixels per frame, so every pixel is lit in some frame), multiplied by
/// `gain` (1 inside the field, 0 in the border), with sensor noise of a few
/// grey levels everywhere, the black border included.
std::vector<cv::Mat> movingFrames(int count, const std::function<double(int, int)>& gain)
{
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 2.0);
  std::vector<cv::Mat> frames;
  for (int f = 0; f < count; ++f)
  {
    cv::Mat frame(Height, Width, CV_8UC3);
    for (int v = 0; v < Height; ++v)
    {
      for (int u = 0; u < Width; ++u)
      {
        const double x = u + 7.0 * f;
        const double y = v + 3.0 * f;
        const double scene = 90.0 + 60.0 * std::sin(x / 9.0) * std::cos(y / 11.0);
        const double value = std::clamp(scene * gain(u, v) + noise(random), 0.0, 255.0);
        const auto level = static_cast<unsigned char>(std::lround(value));
        frame.at<cv::Vec3b>(v, u) = cv::Vec3b(level, level, level);
      }
    }
    frames.push_back(frame);
  }
  return frames;
}

/// A field stop of this centre and radius with an edge 1.5 px wide, as the simulator makes it.
std::function<double(int, int)> disc(double centreU, double centreV, double radius)
{
  return [=](int u, int v)
  { return std::clamp((radius - std::hypot(u - centreU, v - centreV)) / 1.5 + 0.5, 0.0, 1.0); };
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

std::string scratchFile(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("vimlop-test-field-of-view-" + name)).string();
}

/// A bright disc on black (the near wall of an occluding contour on its far
/// side, far darker), centred where the field stop is, plus a smaller contour
/// well inside.
cv::Mat discScene(double centreU, double centreV, double radius)
{
  cv::Mat frame(Height, Width, CV_8UC3, cv::Scalar(0, 0, 0));
  cv::circle(frame, cv::Point(static_cast<int>(centreU), static_cast<int>(centreV)),
    static_cast<int>(radius), cv::Scalar(200, 200, 200), cv::FILLED, cv::LINE_AA);
  cv::circle(frame, cv::Point(static_cast<int>(centreU) + 10, static_cast<int>(centreV)), 30,
    cv::Scalar(40, 40, 40), cv::FILLED, cv::LINE_AA);
  cv::GaussianBlur(frame, frame, cv::Size(0, 0), 0.8);
  return frame;
}

} // namespace

TEST(FieldOfView, DetectionFindsTheCircleOfFramesWithABlackDiscBorder)
{
  const double centreU = 161.5;
  const double centreV = 118.5;
  const double radius = 110.0;
  FieldOfViewOptions options;
  options.marginPx = 0.0;
  const FieldOfView view =
    FieldOfView::detect(movingFrames(12, disc(centreU, centreV, radius)), options);
  ASSERT_FALSE(view.isEverything());
  ASSERT_TRUE(view.isCircular());
  EXPECT_NEAR(view.centreUPx(), centreU, 1.0);
  EXPECT_NEAR(view.centreVPx(), centreV, 1.0);
  EXPECT_NEAR(view.radiusPx(), radius, 2.0);
  EXPECT_TRUE(view.contains(centreU, centreV));
  EXPECT_TRUE(view.contains(centreU + radius - 3.0, centreV));
  EXPECT_FALSE(view.contains(centreU + radius + 3.0, centreV));
  EXPECT_FALSE(view.contains(2.0, 2.0));
}

TEST(FieldOfView, TheMarginShrinksTheDetectedFieldByItsWidth)
{
  const double radius = 100.0;
  FieldOfViewOptions options;
  options.marginPx = 12.0;
  const FieldOfView view =
    FieldOfView::detect(movingFrames(12, disc(159.5, 119.5, radius)), options);
  ASSERT_TRUE(view.isCircular());
  EXPECT_TRUE(view.contains(159.5 + radius - 15.0, 119.5));
  EXPECT_FALSE(view.contains(159.5 + radius - 9.0, 119.5));
  EXPECT_FALSE(view.contains(159.5, 119.5 - radius + 9.0));
}

TEST(FieldOfView, FramesWithoutADarkBorderAreValidEverywhere)
{
  const FieldOfView view =
    FieldOfView::detect(movingFrames(12, [](int, int) { return 1.0; }), FieldOfViewOptions());
  EXPECT_TRUE(view.isEverything());
  EXPECT_FALSE(view.isCircular());
  EXPECT_DOUBLE_EQ(view.validFraction(), 1.0);
  EXPECT_TRUE(view.contains(0.0, 0.0));
  EXPECT_TRUE(view.contains(Width - 1.0, Height - 1.0));
}

TEST(FieldOfView, ADarkPatchThatNeverLightsInsideTheFieldStaysValid)
{
  // A far lumen, dark in every frame, is anatomy: the detected field is filled.
  auto gain = [](int u, int v)
  {
    const double field = disc(159.5, 119.5, 110.0)(u, v);
    return std::hypot(u - 150.0, v - 110.0) < 20.0 ? 0.0 : field;
  };
  FieldOfViewOptions options;
  options.marginPx = 0.0;
  const FieldOfView view = FieldOfView::detect(movingFrames(12, gain), options);
  EXPECT_TRUE(view.contains(150.0, 110.0));
  EXPECT_TRUE(view.isCircular());
}

TEST(FieldOfView, AMaskFileIsReadWhiteInsideAndErodedByTheMargin)
{
  cv::Mat mask(Height, Width, CV_8U, cv::Scalar(0));
  cv::rectangle(mask, cv::Rect(40, 30, 200, 150), cv::Scalar(255), cv::FILLED);
  const std::string path = scratchFile("mask.png");
  ASSERT_TRUE(cv::imwrite(path, mask));
  const FieldOfView view = FieldOfView::fromFile(path, Width, Height, 5.0);
  EXPECT_FALSE(view.isEverything());
  EXPECT_FALSE(view.isCircular());
  EXPECT_TRUE(view.contains(140.0, 100.0));
  EXPECT_TRUE(view.contains(47.0, 100.0));
  EXPECT_FALSE(view.contains(43.0, 100.0));
  EXPECT_FALSE(view.contains(20.0, 100.0));
  std::filesystem::remove(path);
}

TEST(FieldOfView, ABadMaskFileIsRefusedWithAClearMessage)
{
  EXPECT_NE(messageOf([] { FieldOfView::fromFile(scratchFile("missing.png"), Width, Height, 0.0); })
              .find("cannot read the mask image"),
    std::string::npos);
  const std::string small = scratchFile("small.png");
  ASSERT_TRUE(cv::imwrite(small, cv::Mat(10, 20, CV_8U, cv::Scalar(255))));
  EXPECT_NE(messageOf([&] { FieldOfView::fromFile(small, Width, Height, 0.0); })
              .find("is 20x10 px, the frames are 320x240"),
    std::string::npos);
  const std::string black = scratchFile("black.png");
  ASSERT_TRUE(cv::imwrite(black, cv::Mat(Height, Width, CV_8U, cv::Scalar(0))));
  EXPECT_NE(messageOf([&] { FieldOfView::fromFile(black, Width, Height, 0.0); })
              .find("has no white (valid) pixel"),
    std::string::npos);
  const std::string text = scratchFile("text.png");
  {
    std::FILE* file = std::fopen(text.c_str(), "w");
    ASSERT_NE(file, nullptr);
    std::fputs("not a picture", file);
    std::fclose(file);
  }
  EXPECT_NE(messageOf([&] { FieldOfView::fromFile(text, Width, Height, 0.0); })
              .find("cannot read the mask image"),
    std::string::npos);
  for (const std::string& p : { small, black, text })
  {
    std::filesystem::remove(p);
  }
}

TEST(FieldOfView, AGivenCircleIsShrunkByTheMarginAndABadOneRefused)
{
  const FieldOfView view = FieldOfView::circle(Width, Height, 160.0, 120.0, 100.0, 10.0);
  EXPECT_TRUE(view.isCircular());
  EXPECT_TRUE(view.contains(160.0 + 88.0, 120.0));
  EXPECT_FALSE(view.contains(160.0 + 92.0, 120.0));
  EXPECT_NE(messageOf([] { FieldOfView::circle(Width, Height, 160.0, 120.0, 0.0, 10.0); })
              .find("positive radius"),
    std::string::npos);
  EXPECT_NE(
    messageOf([] { FieldOfView::circle(Width, Height, 160.0, 120.0, 50.0, -1.0); }).find("margin"),
    std::string::npos);
}

TEST(FieldOfView, TheTextFormsGiveTheModesAndABadCircleIsRefused)
{
  const FieldOfViewOptions base;
  EXPECT_EQ(FieldOfViewOptions::fromText("none", base).mode, FieldStopMode::None);
  EXPECT_EQ(FieldOfViewOptions::fromText("auto", base).mode, FieldStopMode::Auto);
  const FieldOfViewOptions file = FieldOfViewOptions::fromText("stop.png", base);
  EXPECT_EQ(file.mode, FieldStopMode::File);
  EXPECT_EQ(file.maskFile, "stop.png");
  const FieldOfViewOptions circle = FieldOfViewOptions::fromText("circle:160.5,120,99", base);
  EXPECT_EQ(circle.mode, FieldStopMode::Circle);
  EXPECT_DOUBLE_EQ(circle.centreUPx, 160.5);
  EXPECT_DOUBLE_EQ(circle.centreVPx, 120.0);
  EXPECT_DOUBLE_EQ(circle.radiusPx, 99.0);
  EXPECT_EQ(circle.toText(), "circle:160.5,120,99");
  for (const char* bad : { "circle:1,2", "circle:1,2,-3", "circle:1,2,3,4", "circle:a,b,c", "" })
  {
    EXPECT_NE(
      messageOf([&] { FieldOfViewOptions::fromText(bad, base); }).find("field stop: expected"),
      std::string::npos)
      << bad;
  }
}

TEST(FieldOfView, TheContourDetectorDropsPointsNearTheFieldStopsEdgeWithTheMaskOnly)
{
  // The field stop's edge is a bright-to-black step whose dark side stays
  // dark: without the mask the detector takes it for an occluding contour.
  const double centreU = 160.0;
  const double centreV = 120.0;
  const double radius = 100.0;
  const cv::Mat frame = discScene(centreU, centreV, radius);
  const OccludingContourDetector detector;
  const std::vector<ContourPoint> all = detector.detect(frame);
  auto onEdge = [&](const ContourPoint& p)
  { return std::abs((p.pixel - Eigen::Vector2d(centreU, centreV)).norm() - radius) < 4.0; };
  const auto edgeCount = std::count_if(all.begin(), all.end(), onEdge);
  ASSERT_GT(edgeCount, 50);

  const FieldOfView view = FieldOfView::circle(Width, Height, centreU, centreV, radius, 12.0);
  OccludingContourDetector::MaskedDetectionCounts counts;
  const std::vector<ContourPoint> masked = detector.detect(frame, view.mask(), &counts);
  EXPECT_EQ(std::count_if(masked.begin(), masked.end(), onEdge), 0);
  // The inner contour is kept, the same points as without the mask.
  const auto inner =
    std::count_if(all.begin(), all.end(), [&](const ContourPoint& p) { return !onEdge(p); });
  EXPECT_EQ(static_cast<long>(masked.size()), static_cast<long>(inner));
  EXPECT_GT(masked.size(), 30u);
  EXPECT_EQ(counts.detected, all.size());
  EXPECT_EQ(counts.dropped, static_cast<size_t>(edgeCount));

  // Without a mask (an empty one) the points are those of detect(frame).
  const std::vector<ContourPoint> unmasked = detector.detect(frame, cv::Mat());
  ASSERT_EQ(unmasked.size(), all.size());
  for (size_t k = 0; k < all.size(); ++k)
  {
    EXPECT_EQ(unmasked[k].pixel, all[k].pixel);
  }
  EXPECT_NE(messageOf([&] { detector.detect(frame, cv::Mat(10, 10, CV_8U, cv::Scalar(255))); })
              .find("mask must be"),
    std::string::npos);
}
