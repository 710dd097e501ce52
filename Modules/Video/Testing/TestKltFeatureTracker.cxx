#include <vimlop/Video/KltFeatureTracker.h>

#include "ErrorMessage.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>

using namespace vimlop;

namespace
{

/// A grey picture of smoothed random blobs (a texture KLT can follow),
/// sampled at (u - shiftX, v - shiftY): the same texture moved by the shift.
cv::Mat texture(double shiftX, double shiftY, int width = 160, int height = 120)
{
  // Fine random dots, blurred into blobs, drawn on a larger canvas so that
  // a shift brings texture in from beyond the border.
  cv::Mat dots(height + 40, width + 40, CV_32F);
  std::uint32_t state = 7u;
  for (int v = 0; v < dots.rows; ++v)
  {
    for (int u = 0; u < dots.cols; ++u)
    {
      state = state * 1664525u + 1013904223u;
      dots.at<float>(v, u) = static_cast<float>(state >> 24);
    }
  }
  cv::GaussianBlur(dots, dots, cv::Size(0, 0), 2.0);
  cv::Mat moved;
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, shiftX - 20, 0, 1, shiftY - 20);
  cv::warpAffine(dots, moved, shift, cv::Size(width, height), cv::INTER_CUBIC);
  // One contrast stretch for every shift (about 127 +- 60 grey levels), so
  // that the frames differ by the motion only.
  cv::Mat grey;
  moved.convertTo(grey, CV_8U, 6.0, 127.5 - 6.0 * 127.5);
  return grey;
}

} // namespace

TEST(KltFeatureTracker, FollowsCornersOfATextureMovedByASubpixelShift)
{
  KltFeatureTracker tracker;
  tracker.reset(texture(0.0, 0.0));
  std::vector<Eigen::Vector2d> pixels = tracker.detect(50, {});
  ASSERT_GE(pixels.size(), 30u);
  const std::vector<Eigen::Vector2d> before = pixels;
  const std::vector<char> kept = tracker.track(texture(2.3, -1.6), pixels);
  // Every feature within a quarter pixel (those whose window reaches the
  // border after the move are the worst, about 0.2 px), half within 0.1 px.
  std::vector<double> errors;
  for (std::size_t i = 0; i < pixels.size(); ++i)
  {
    if (kept[i])
    {
      const Eigen::Vector2d error = pixels[i] - before[i] - Eigen::Vector2d(2.3, -1.6);
      EXPECT_LT(error.norm(), 0.25) << i << " at " << before[i].transpose();
      errors.push_back(error.norm());
    }
  }
  const int followed = static_cast<int>(errors.size());
  std::nth_element(errors.begin(), errors.begin() + followed / 2, errors.end());
  EXPECT_LT(errors[static_cast<std::size_t>(followed / 2)], 0.1); // measured 0.06
  EXPECT_GE(followed, static_cast<int>(0.8 * pixels.size()));
}

TEST(KltFeatureTracker, FollowsTextureWhoseLightingChangesAsTheScopeMoves)
{
  // The second frame is the texture moved and lit by a headlight that
  // came nearer: brighter, more on the left than on the right. Dividing
  // the illumination out keeps the features on the texture; following raw
  // brightness makes them slide.
  auto lit = [](const cv::Mat& grey)
  {
    cv::Mat value;
    grey.convertTo(value, CV_32F);
    for (int u = 0; u < value.cols; ++u)
    {
      value.col(u) *= 1.4 - 0.5 * u / value.cols;
    }
    cv::Mat out;
    value.convertTo(out, CV_8U);
    return out;
  };
  auto medianError = [&](double illuminationSigmaPx)
  {
    KltFeatureTrackerOptions options;
    options.illuminationSigmaPx = illuminationSigmaPx;
    KltFeatureTracker tracker(options);
    tracker.reset(texture(0.0, 0.0));
    std::vector<Eigen::Vector2d> pixels = tracker.detect(50, {});
    const std::vector<Eigen::Vector2d> before = pixels;
    const std::vector<char> kept = tracker.track(lit(texture(1.5, 0.5)), pixels);
    std::vector<double> errors;
    for (std::size_t i = 0; i < pixels.size(); ++i)
    {
      // A lost feature counts as far off.
      errors.push_back(
        kept[i] ? (pixels[i] - before[i] - Eigen::Vector2d(1.5, 0.5)).norm() : 100.0);
    }
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    return errors[errors.size() / 2];
  };
  const double normalised = medianError(8.0);
  const double raw = medianError(0.0);
  std::printf(
    "median error: %.3f px with the illumination divided out, %.3f px without\n", normalised, raw);
  // Measured when written: 0.011 px and 0.113 px.
  EXPECT_LT(normalised, 0.05);
  EXPECT_GT(raw, 3.0 * normalised);
}

TEST(KltFeatureTracker, DropsFeaturesWhoseTextureIsGone)
{
  // The next frame is flat grey: nothing can be followed into it.
  KltFeatureTracker tracker;
  tracker.reset(texture(0.0, 0.0));
  std::vector<Eigen::Vector2d> pixels = tracker.detect(40, {});
  ASSERT_FALSE(pixels.empty());
  const std::vector<char> kept = tracker.track(cv::Mat(120, 160, CV_8U, cv::Scalar(128)), pixels);
  int followed = 0;
  for (char k : kept)
  {
    followed += k ? 1 : 0;
  }
  EXPECT_EQ(followed, 0);
}

TEST(KltFeatureTracker, DetectsNewCornersOnlyInTheMaskAndAwayFromTrackedOnes)
{
  KltFeatureTrackerOptions options;
  options.minCornerDistancePx = 10.0;
  KltFeatureTracker tracker(options);
  tracker.reset(texture(0.0, 0.0));
  cv::Mat leftHalf(120, 160, CV_8U, cv::Scalar(0));
  leftHalf(cv::Rect(0, 0, 80, 120)).setTo(255);
  const std::vector<Eigen::Vector2d> existing{ { 40.0, 60.0 } };
  const std::vector<Eigen::Vector2d> found = tracker.detect(100, existing, leftHalf);
  ASSERT_FALSE(found.empty());
  for (const Eigen::Vector2d& p : found)
  {
    EXPECT_LT(p.x(), 80.0);
    // Half a window (21 px) from the border.
    EXPECT_GE(p.x(), 10.0);
    EXPECT_GE(p.y(), 10.0);
    EXPECT_LE(p.y(), 109.0);
    EXPECT_GE((p - existing[0]).norm(), 10.0 - 1.0);
  }
  EXPECT_TRUE(tracker.detect(0, {}).empty());
}

TEST(KltFeatureTracker, RefusesBadFramesAndOptionsWithAClearMessage)
{
  KltFeatureTracker tracker;
  std::vector<Eigen::Vector2d> none;
  EXPECT_EQ(fixtures::errorMessageOf([&] { tracker.track(texture(0, 0), none); }),
    "feature tracking: no current frame (reset() first)");
  EXPECT_EQ(fixtures::errorMessageOf([&] { tracker.reset(cv::Mat()); }),
    "feature tracking: the frame is empty");
  EXPECT_EQ(fixtures::errorMessageOf([&] { tracker.reset(cv::Mat(10, 10, CV_32F)); }),
    "feature tracking: frames must be 8-bit grey or BGR, not 1-channel with OpenCV depth 5");
  tracker.reset(texture(0, 0));
  EXPECT_EQ(fixtures::errorMessageOf([&] { tracker.track(texture(0, 0, 80, 60), none); }),
    "feature tracking: a frame of 80 x 60 pixels after frames of 160 x 120");
  EXPECT_EQ(fixtures::errorMessageOf([&] { tracker.detect(5, {}, cv::Mat(10, 10, CV_8U)); }),
    "feature tracking: a mask of 10 x 10 pixels for frames of 160 x 120");
  KltFeatureTrackerOptions even;
  even.windowPx = 20;
  EXPECT_EQ(fixtures::errorMessageOf([&] { KltFeatureTracker t(even); }),
    "feature tracking: the window must be an odd number of pixels, at least 5, not 20");
  KltFeatureTrackerOptions backward;
  backward.maxForwardBackwardPx = 0.0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { KltFeatureTracker t(backward); }),
    "feature tracking: the forward-backward tolerance must be positive, not 0 px");
}
