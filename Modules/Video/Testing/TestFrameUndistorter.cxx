#include <vimlop/Video/FrameUndistorter.h>

#include "ErrorMessage.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

using namespace vimlop;

namespace
{

/// Where the lens of `k` puts the ideal pixel `ideal` (OpenCV's projection).
cv::Point2d distortedPixel(const PinholeCamera& k, const cv::Point2d& ideal)
{
  const cv::Mat matrix = (cv::Mat_<double>(3, 3) << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  cv::Mat coefficients(1, static_cast<int>(k.distortion.size()), CV_64F);
  for (int i = 0; i < coefficients.cols; ++i)
  {
    coefficients.at<double>(i) = k.distortion[i];
  }
  const std::vector<cv::Point3d> ray{ { (ideal.x - k.cx) / k.fx, (ideal.y - k.cy) / k.fy, 1.0 } };
  std::vector<cv::Point2d> pixel;
  const cv::Mat zero = cv::Mat::zeros(3, 1, CV_64F);
  if (k.lensModel == LensModel::Fisheye)
  {
    cv::fisheye::projectPoints(ray, pixel, zero, zero, matrix, coefficients);
  }
  else
  {
    cv::projectPoints(ray, zero, zero, matrix, coefficients, pixel);
  }
  return pixel[0];
}

/// The centroid of the bright pixels of a grey picture.
cv::Point2d brightCentroid(const cv::Mat& grey)
{
  const cv::Moments m = cv::moments(grey > 100, true);
  return { m.m10 / m.m00, m.m01 / m.m00 };
}

} // namespace

TEST(FrameUndistorter, PutsADotSeenThroughTheLensWhereThePinholeSeesIt)
{
  for (const LensModel model : { LensModel::RadialTangential, LensModel::Fisheye })
  {
    PinholeCamera k = PinholeCamera::simulatedEndoscope();
    k.lensModel = model;
    k.distortion = model == LensModel::Fisheye ? Eigen::Vector4d(0.05, 0.01, 0.0, 0.0)
                                               : Eigen::Vector4d(-0.3, 0.08, 0.0, 0.0);
    // A dot near the corner, where the lens moves it most.
    const cv::Point2d ideal(270.0, 50.0);
    const cv::Point2d seen = distortedPixel(k, ideal);
    ASSERT_GT(cv::norm(seen - ideal), 5.0);
    cv::Mat frame(k.heightPx, k.widthPx, CV_8UC1, cv::Scalar(0));
    cv::circle(frame,
      cv::Point(static_cast<int>(std::lround(seen.x)), static_cast<int>(std::lround(seen.y))), 3,
      cv::Scalar(255), cv::FILLED);
    const FrameUndistorter undistorter(k);
    EXPECT_TRUE(undistorter.distorts());
    EXPECT_FALSE(undistorter.pinhole().hasDistortion());
    EXPECT_EQ(undistorter.pinhole().fx, k.fx);
    const cv::Point2d found = brightCentroid(undistorter.undistort(frame));
    // Within a pixel and a half: the dot was drawn at a whole pixel and
    // blurred by the remap.
    EXPECT_LT(cv::norm(found - ideal), 1.5) << static_cast<int>(model) << " " << found;
  }
}

TEST(FrameUndistorter, LeavesFramesOfAPinholeAsTheyAreAndRefusesOtherSizes)
{
  const FrameUndistorter undistorter(PinholeCamera::simulatedEndoscope());
  EXPECT_FALSE(undistorter.distorts());
  const cv::Mat frame(240, 320, CV_8UC3, cv::Scalar(10, 20, 30));
  const cv::Mat same = undistorter.undistort(frame);
  EXPECT_EQ(same.data, frame.data);
  EXPECT_EQ(fixtures::errorMessageOf([&] { undistorter.undistort(cv::Mat(10, 10, CV_8UC3)); }),
    "undistortion: a frame of 10 x 10 pixels for a camera of 320 x 240");
}
