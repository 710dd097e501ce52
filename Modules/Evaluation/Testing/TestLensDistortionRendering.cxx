#include "TestFolders.h"
#include <vimlop/Evaluation/LensDistortionRendering.h>
#include <vimlop/Video/FrameSequence.h>
#include <vimlop/Video/IntrinsicsIO.h>
#include <vimlop/Video/VideoInput.h>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>
#include <vector>

using namespace vimlop;

namespace
{

/// A wide-angle endoscope's lens: strong barrel distortion, a little tangential.
PinholeCamera barrelCamera()
{
  PinholeCamera k = PinholeCamera::simulatedEndoscope();
  k.distortion = Eigen::Vector4d(-0.3, 0.05, 0.001, -0.0015);
  return k;
}

/// A wide-angle endoscope's fisheye lens: nearly equidistant, with small
/// coefficients of the size OpenCV's fisheye calibration gives such lenses.
PinholeCamera fisheyeCamera()
{
  PinholeCamera k = PinholeCamera::simulatedEndoscope();
  k.lensModel = LensModel::Fisheye;
  k.distortion = Eigen::Vector4d(0.03, -0.01, 0.002, -0.0005);
  return k;
}

/// A pinhole picture of one straight horizontal line at row `rowPx`: a
/// Gaussian profile across it (std 1.2 px), so that its centre is found to
/// a small fraction of a pixel.
cv::Mat horizontalLine(const PinholeCamera& k, double rowPx)
{
  cv::Mat picture(k.heightPx, k.widthPx, CV_32F);
  for (int v = 0; v < k.heightPx; ++v)
  {
    const float value = static_cast<float>(255.0 * std::exp(-0.5 * std::pow((v - rowPx) / 1.2, 2)));
    picture.row(v).setTo(value);
  }
  return picture;
}

/// Per column, the intensity-weighted centre of the line (columns where it is seen).
std::vector<cv::Point2d> lineCentres(const cv::Mat& picture, int firstColumn, int lastColumn)
{
  std::vector<cv::Point2d> centres;
  for (int u = firstColumn; u <= lastColumn; ++u)
  {
    double sum = 0.0;
    double weighted = 0.0;
    for (int v = 0; v < picture.rows; ++v)
    {
      const double value = picture.at<float>(v, u);
      if (value > 1.0)
      {
        sum += value;
        weighted += value * v;
      }
    }
    if (sum > 0.0)
    {
      centres.emplace_back(u, weighted / sum);
    }
  }
  return centres;
}

/// The largest distance of `points` from the straight line through the first and the last.
double largestDeviationFromTheChordPx(const std::vector<cv::Point2d>& points)
{
  const cv::Point2d a = points.front();
  const cv::Point2d d = points.back() - a;
  double largest = 0.0;
  for (const cv::Point2d& p : points)
  {
    largest = std::max(largest, std::abs(d.x * (p.y - a.y) - d.y * (p.x - a.x)) / cv::norm(d));
  }
  return largest;
}

} // namespace

TEST(LensDistortionRendering, WithoutDistortionTheMapIsTheIdentity)
{
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  EXPECT_FALSE(k.hasDistortion());
  PinholeCamera zeros = k;
  zeros.distortion = Eigen::Vector4d::Zero();
  EXPECT_FALSE(zeros.hasDistortion());
  const cv::Mat map = distortedToPinholeMap(zeros, k);
  EXPECT_EQ(map.at<cv::Vec2f>(17, 101), cv::Vec2f(101.0f, 17.0f));
  const PinholeCamera covering = pinholeCameraCovering(zeros);
  EXPECT_EQ(covering.widthPx, k.widthPx + 2);
  EXPECT_DOUBLE_EQ(covering.cx, k.cx + 1.0);
}

TEST(LensDistortionRendering, DistortionBendsStraightLinesAndTheWrittenCoefficientsStraightenThem)
{
  const PinholeCamera distorted = barrelCamera();
  ASSERT_TRUE(distorted.hasDistortion());
  PinholeCamera pinhole = distorted;
  pinhole.removeDistortion();
  const double rowPx = distorted.cy + 80.0;
  const cv::Mat straight = horizontalLine(pinhole, rowPx);
  const cv::Mat bent = renderLensDistortion(straight, distortedToPinholeMap(distorted, pinhole));

  // In the pinhole picture the line is straight; in the distorted one it bows
  // towards the centre by several pixels (barrel distortion).
  EXPECT_LT(largestDeviationFromTheChordPx(lineCentres(straight, 20, 300)), 0.01);
  const std::vector<cv::Point2d> seen = lineCentres(bent, 40, 280);
  ASSERT_GT(seen.size(), 200u);
  EXPECT_GT(largestDeviationFromTheChordPx(seen), 5.0);

  // The coefficients as a user reads them from intrinsics.yaml undistort the
  // line's points back onto the straight row, to a small fraction of a pixel.
  const std::string path =
    (std::filesystem::path(::testing::TempDir()) / "distorted-intrinsics.yaml").string();
  writeIntrinsics(distorted, path);
  const PinholeCamera read = readIntrinsics(path);
  ASSERT_EQ(read.distortion.size(), 4);
  cv::Mat k = (cv::Mat_<double>(3, 3) << read.fx, 0, read.cx, 0, read.fy, read.cy, 0, 0, 1);
  cv::Mat d(1, 4, CV_64F);
  for (int i = 0; i < 4; ++i)
  {
    d.at<double>(0, i) = read.distortion[i];
  }
  std::vector<cv::Point2d> undistorted;
  cv::undistortPoints(seen, undistorted, k, d, cv::noArray(), k,
    cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-12));
  double largest = 0.0;
  for (const cv::Point2d& p : undistorted)
  {
    largest = std::max(largest, std::abs(p.y - rowPx));
  }
  EXPECT_LT(largest, 0.2);
  EXPECT_LT(largestDeviationFromTheChordPx(undistorted), 0.2);
}

TEST(LensDistortionRendering, BarrelDistortionNeedsAWiderPinholeViewAndBlacksOutWhereItFolds)
{
  // k1 = -0.4 folds back at a normalized radius of 1 / sqrt(1.2) = 0.91 (182
  // px at f = 200): the corners of the 320 x 240 frame (radius 200 px) have no source.
  PinholeCamera distorted = PinholeCamera::simulatedEndoscope();
  distorted.distortion = Eigen::Vector4d(-0.4, 0.0, 0.0, 0.0);
  const PinholeCamera pinhole = pinholeCameraCovering(distorted);
  EXPECT_GT(pinhole.widthPx, distorted.widthPx);
  EXPECT_FALSE(pinhole.hasDistortion());
  EXPECT_EQ(pinhole.cx - distorted.cx, std::round(pinhole.cx - distorted.cx));
  const cv::Mat map = distortedToPinholeMap(distorted, pinhole);
  EXPECT_LT(map.at<cv::Vec2f>(0, 0)[0], -1000.0f);
  // The centre sees the same ray in both pictures; a pixel 100 px right of it
  // comes from farther out in the pinhole picture.
  const cv::Vec2f centre = map.at<cv::Vec2f>(120, 160);
  EXPECT_NEAR(centre[0], 160.0 + (pinhole.cx - distorted.cx), 0.1);
  const cv::Vec2f right = map.at<cv::Vec2f>(120, 260);
  EXPECT_GT(right[0] - pinhole.cx, 100.0 + 10.0);

  cv::Mat white(pinhole.heightPx, pinhole.widthPx, CV_8UC3, cv::Scalar::all(200));
  const cv::Mat picture = renderLensDistortion(white, map);
  EXPECT_EQ(picture.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(picture.at<cv::Vec3b>(120, 160), cv::Vec3b(200, 200, 200));

  DepthMap depth;
  depth.widthPx = pinhole.widthPx;
  depth.heightPx = pinhole.heightPx;
  depth.depthMm.assign(static_cast<size_t>(depth.widthPx) * depth.heightPx, 0.0f);
  for (int v = 0; v < depth.heightPx; ++v)
  {
    for (int u = 0; u < depth.widthPx; ++u)
    {
      depth.depthMm[static_cast<size_t>(v) * depth.widthPx + u] = static_cast<float>(u);
    }
  }
  const DepthMap seen = renderLensDistortion(depth, map);
  EXPECT_EQ(seen.widthPx, 320);
  EXPECT_EQ(seen.at(0, 0), DepthMap::noSurface());
  EXPECT_EQ(seen.at(260, 120), std::round(right[0]));
}

TEST(LensDistortionRendering, AFisheyeIsADistortionEvenWithZeroCoefficients)
{
  PinholeCamera equidistant = PinholeCamera::simulatedEndoscope();
  equidistant.lensModel = LensModel::Fisheye;
  equidistant.distortion = Eigen::Vector4d::Zero();
  EXPECT_TRUE(equidistant.hasDistortion());
  // Pixel (260, 120), (100.5, 0.5) px from the principal point, sees the ray
  // at theta = its distance / f from the axis (equidistant), which the
  // pinhole puts tan(theta) / theta times as far out.
  PinholeCamera pinhole = equidistant;
  pinhole.removeDistortion();
  EXPECT_FALSE(pinhole.hasDistortion());
  const cv::Vec2f seen = distortedToPinholeMap(equidistant, pinhole).at<cv::Vec2f>(120, 260);
  const double theta = std::hypot(100.5, 0.5) / 200.0;
  const double outwards = std::tan(theta) / theta;
  EXPECT_NEAR(seen[0], pinhole.cx + 100.5 * outwards, 1e-3);
  EXPECT_NEAR(seen[1], pinhole.cy + 0.5 * outwards, 1e-3);
  EXPECT_GT(outwards, 1.08);
}

TEST(LensDistortionRendering, AFisheyeNeedsAWiderPinholeViewAndBlacksOutRaysAtNinetyDegrees)
{
  // At f = 100 px the frame's border is 1.6 rad off the axis (160 px / f),
  // beyond the 90° that a pinhole picture can hold.
  PinholeCamera fisheye = fisheyeCamera();
  fisheye.fx = fisheye.fy = 100.0;
  const PinholeCamera pinhole = pinholeCameraCovering(fisheye);
  EXPECT_FALSE(pinhole.hasDistortion());
  EXPECT_GT(pinhole.widthPx, 2 * fisheye.widthPx);
  EXPECT_LE(pinhole.widthPx, 4 * fisheye.widthPx + 4);
  const cv::Mat map = distortedToPinholeMap(fisheye, pinhole);
  EXPECT_LT(map.at<cv::Vec2f>(120, 0)[0], -1000.0f);
  EXPECT_LT(map.at<cv::Vec2f>(0, 0)[0], -1000.0f);
  const cv::Vec2f centre = map.at<cv::Vec2f>(120, 160);
  EXPECT_NEAR(centre[0], 160.0 + (pinhole.cx - fisheye.cx), 0.1);
  cv::Mat white(pinhole.heightPx, pinhole.widthPx, CV_8UC3, cv::Scalar::all(200));
  const cv::Mat picture = renderLensDistortion(white, map);
  EXPECT_EQ(picture.at<cv::Vec3b>(120, 0), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(picture.at<cv::Vec3b>(120, 160), cv::Vec3b(200, 200, 200));
}

TEST(
  LensDistortionRendering, AFisheyeBendsStraightLinesAndTheRegistrationsUndistortionStraightensThem)
{
  const PinholeCamera fisheye = fisheyeCamera();
  const PinholeCamera pinhole = pinholeCameraCovering(fisheye);
  // The line 80 px below the centre in the true pinhole picture (0.4 in
  // normalized coordinates).
  const double rowPx = fisheye.cy + 80.0;
  const cv::Mat straight = horizontalLine(pinhole, pinhole.cy + 80.0);
  const cv::Mat bent = renderLensDistortion(straight, distortedToPinholeMap(fisheye, pinhole));
  const std::vector<cv::Point2d> seen = lineCentres(bent, 20, 300);
  ASSERT_GT(seen.size(), 250u);
  EXPECT_GT(largestDeviationFromTheChordPx(seen), 5.0);

  // The frame and the intrinsics as a user has them, loaded as the
  // registration loads them (idealFrames: cv::fisheye's undistortion).
  const std::filesystem::path folder = fixtures::freshTestFolder("fisheye-line");
  std::filesystem::create_directories(folder / "frames");
  cv::Mat frame;
  bent.convertTo(frame, CV_8U);
  cv::cvtColor(frame, frame, cv::COLOR_GRAY2BGR);
  ASSERT_TRUE(cv::imwrite((folder / "frames" / "frame000.png").string(), frame));
  const std::string intrinsicsPath = (folder / "intrinsics.yaml").string();
  writeIntrinsics(fisheye, intrinsicsPath);
  const PinholeCamera read = readIntrinsics(intrinsicsPath);
  ASSERT_EQ(read.lensModel, LensModel::Fisheye);
  const std::vector<cv::Mat> ideal = idealFrames(FrameSequence::load((folder / "frames").string()),
    read, (folder / "frames").string(), intrinsicsPath, nullptr);
  ASSERT_EQ(ideal.size(), 1u);
  cv::Mat grey;
  cv::cvtColor(ideal[0], grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(grey, CV_32F);
  const std::vector<cv::Point2d> undistorted = lineCentres(grey, 20, 300);
  ASSERT_GT(undistorted.size(), 250u);
  double largest = 0.0;
  for (const cv::Point2d& p : undistorted)
  {
    largest = std::max(largest, std::abs(p.y - rowPx));
  }
  EXPECT_LT(largest, 0.3);
  EXPECT_LT(largestDeviationFromTheChordPx(undistorted), 0.3);
}
