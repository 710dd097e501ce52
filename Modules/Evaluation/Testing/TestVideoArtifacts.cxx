#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/VideoArtifacts.h>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

using namespace vimlop;

namespace
{

/// A plane facing the camera at `zMm` over the whole image.
DepthMap planeDepth(const PinholeCamera& k, float zMm)
{
  DepthMap d;
  d.widthPx = k.widthPx;
  d.heightPx = k.heightPx;
  d.depthMm.assign(static_cast<size_t>(k.widthPx) * k.heightPx, zMm);
  return d;
}

/// A picture with stripes along both axes (periods 8 and 11 px), CV_32FC3.
cv::Mat stripes(int w, int h)
{
  cv::Mat picture(h, w, CV_32FC3);
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      const float g = static_cast<float>(
        120.0 + 50.0 * std::sin(2.0 * M_PI * u / 8.0) + 50.0 * std::sin(2.0 * M_PI * v / 11.0));
      picture.at<cv::Vec3f>(v, u) = cv::Vec3f(g, g, g);
    }
  }
  return picture;
}

/// The sum of squared differences between neighbours along u (dx 1) or v (dy 1), away from the
/// border.
double gradientEnergy(const cv::Mat& picture, int dx, int dy)
{
  double energy = 0.0;
  for (int v = 10; v + 10 < picture.rows; ++v)
  {
    for (int u = 10; u + 10 < picture.cols; ++u)
    {
      const double d = picture.at<cv::Vec3f>(v + dy, u + dx)[1] - picture.at<cv::Vec3f>(v, u)[1];
      energy += d * d;
    }
  }
  return energy;
}

CameraPose at(double xMm)
{
  CameraPose p;
  p.centre = Eigen::Vector3d(xMm, 0.0, 0.0);
  return p;
}

std::string messageOf(const std::function<void()>& run)
{
  try
  {
    run();
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "(no error)";
}

} // namespace

TEST(VideoArtifacts, AreOffByDefaultAndValid)
{
  const VideoArtifactOptions o;
  EXPECT_TRUE(o.isOff());
  EXPECT_FALSE(o.actsOnLight());
  EXPECT_NO_THROW(o.validate());
  VideoArtifactOptions compressed;
  compressed.compression = VideoCompression::Mjpg;
  EXPECT_FALSE(compressed.isOff());
  EXPECT_FALSE(compressed.actsOnLight()); // compression acts on the recorded video, not the light
}

TEST(VideoArtifacts, TheExposurePosesSpanTheExposureCentredOnTheFrame)
{
  const std::vector<CameraPose> cameras = { at(-3.0), at(0.0), at(3.0) };
  // 30 fps, 1/30 s: from half a frame before to half a frame after, 3 mm per frame.
  const std::vector<CameraPose> poses = exposurePoses(cameras, 1, 30.0, 1.0 / 30.0, 5);
  ASSERT_EQ(poses.size(), 5u);
  EXPECT_NEAR(poses.front().centre.x(), -1.5, 1e-12);
  EXPECT_NEAR(poses[2].centre.x(), 0.0, 1e-12);
  EXPECT_NEAR(poses.back().centre.x(), 1.5, 1e-12);
  // Beyond the last frame the last step's velocity goes on.
  EXPECT_NEAR(exposurePoses(cameras, 2, 30.0, 1.0 / 30.0, 5).back().centre.x(), 4.5, 1e-12);
}

TEST(VideoArtifacts, MotionBlurLowersTheGradientEnergyAlongTheMotionOnly)
{
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  DepthMap depth = planeDepth(k, 50.0f);
  // A hole with no surface in the middle: it moves with its neighbours.
  for (int v = 100; v < 140; ++v)
  {
    for (int u = 140; u < 180; ++u)
    {
      depth.depthMm[static_cast<size_t>(v) * k.widthPx + u] = DepthMap::noSurface();
    }
  }
  const cv::Mat sharp = stripes(k.widthPx, k.heightPx);
  // 2 mm per frame sideways at 50 mm and f = 200 px: 8 px per frame, 4 px
  // during an exposure of half the frame period, half a stripe period.
  const std::vector<CameraPose> cameras = { at(-2.0), at(0.0), at(2.0) };
  const cv::Mat blurred =
    renderMotionBlur(sharp, depth, k, cameras[1], exposurePoses(cameras, 1, 30.0, 1.0 / 60.0, 9));
  ASSERT_EQ(blurred.type(), sharp.type());
  EXPECT_LT(gradientEnergy(blurred, 1, 0), 0.6 * gradientEnergy(sharp, 1, 0));
  EXPECT_GT(gradientEnergy(blurred, 0, 1), 0.95 * gradientEnergy(sharp, 0, 1));
  // Inside the hole too.
  const cv::Rect hole(145, 105, 30, 30);
  EXPECT_LT(
    gradientEnergy(blurred(hole).clone(), 1, 0), 0.6 * gradientEnergy(sharp(hole).clone(), 1, 0));
}

TEST(VideoArtifacts, MotionBlurLeavesTheFrameOfAStaticCameraUnchanged)
{
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  const cv::Mat sharp = stripes(k.widthPx, k.heightPx);
  const std::vector<CameraPose> cameras = { at(1.0), at(1.0), at(1.0) };
  const cv::Mat same = renderMotionBlur(
    sharp, planeDepth(k, 40.0f), k, cameras[1], exposurePoses(cameras, 1, 30.0, 1.0 / 30.0, 7));
  EXPECT_EQ(cv::norm(same, sharp, cv::NORM_INF), 0.0);
}

TEST(VideoArtifacts, SpecularHighlightsSaturatePixelsOnlyWhereTheSurfaceFacesTheCamera)
{
  // A plane facing the camera: its normal is the ray's reverse at the
  // principal point and turns away from the ray by atan(r / f) at r pixels
  // from it, so an 8 degree highlight is a disc of radius 200 tan 8° = 28 px.
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  const cv::Mat highlights = specularHighlights(planeDepth(k, 30.0f), k, 1.5, 8.0);
  cv::Mat light(k.heightPx, k.widthPx, CV_32FC3, cv::Scalar::all(100.0));
  addSpecularHighlights(light, highlights);
  applyExposure(light, 1.0);
  int saturated = 0;
  for (int v = 0; v < k.heightPx; ++v)
  {
    for (int u = 0; u < k.widthPx; ++u)
    {
      const double angleDeg = std::atan(std::hypot(u - k.cx, v - k.cy) / k.fx) * 180.0 / M_PI;
      const cv::Vec3f pixel = light.at<cv::Vec3f>(v, u);
      if (pixel == cv::Vec3f(255.0f, 255.0f, 255.0f))
      {
        ++saturated;
        EXPECT_LT(angleDeg, 8.0) << u << ", " << v;
      }
      else if (angleDeg >= 8.0)
      {
        EXPECT_EQ(pixel, cv::Vec3f(100.0f, 100.0f, 100.0f)) << u << ", " << v;
      }
    }
  }
  // Saturated where 100 + 1.5 × 255 × (1 − (α/8°)²) ≥ 255: α < 6.4°, r < 22 px.
  EXPECT_GT(saturated, 1200);
  EXPECT_LT(saturated, 1700);
  // A plane at 60° to the view: nowhere facing the camera, no highlight.
  DepthMap tilted = planeDepth(k, 30.0f);
  for (int v = 0; v < k.heightPx; ++v)
  {
    for (int u = 0; u < k.widthPx; ++u)
    {
      // z = 30 + tan(60°) x on the ray through (u, v): x = (u - cx) z / fx.
      const double slope = std::tan(M_PI / 3.0) * (u - k.cx) / k.fx;
      tilted.depthMm[static_cast<size_t>(v) * k.widthPx + u] =
        static_cast<float>(30.0 / (1.0 - slope));
      if (slope >= 0.9)
      {
        tilted.depthMm[static_cast<size_t>(v) * k.widthPx + u] = DepthMap::noSurface();
      }
    }
  }
  EXPECT_EQ(cv::countNonZero(specularHighlights(tilted, k, 1.5, 8.0)), 0);
}

TEST(VideoArtifacts, AGainAboveOneClipsAtFullScaleAndOneBelowDarkens)
{
  cv::Mat ramp(1, 256, CV_32FC3);
  for (int u = 0; u < 256; ++u)
  {
    ramp.at<cv::Vec3f>(0, u) = cv::Vec3f::all(static_cast<float>(u));
  }
  cv::Mat bright = ramp.clone();
  applyExposure(bright, 2.0);
  cv::Mat dark = ramp.clone();
  applyExposure(dark, 0.5);
  for (int u = 0; u < 256; ++u)
  {
    EXPECT_EQ(bright.at<cv::Vec3f>(0, u)[0], u >= 128 ? 255.0f : 2.0f * u);
    EXPECT_EQ(dark.at<cv::Vec3f>(0, u)[2], 0.5f * u);
  }
}

TEST(VideoArtifacts, ShotNoiseVarianceGrowsWithIntensity)
{
  // Left half at 20 grey levels, right half at 200; shot noise 0.5: variance 10 and 100.
  cv::Mat light(200, 400, CV_32FC3, cv::Scalar::all(20.0));
  light(cv::Rect(200, 0, 200, 200)).setTo(cv::Scalar::all(200.0));
  auto variances = [&light](double sigma, double shot)
  {
    const cv::Mat noisy = addSensorNoise(light, sigma, shot, 7);
    std::vector<double> result;
    for (const cv::Rect half : { cv::Rect(0, 0, 200, 200), cv::Rect(200, 0, 200, 200) })
    {
      cv::Scalar mean, sd;
      cv::meanStdDev(noisy(half), mean, sd);
      result.push_back(sd[0] * sd[0]);
    }
    return result;
  };
  const std::vector<double> shot = variances(0.0, 0.5);
  EXPECT_NEAR(shot[0], 10.0, 1.0);
  EXPECT_NEAR(shot[1], 100.0, 6.0);
  // The Gaussian noise alone is the same everywhere: 1.5² plus rounding's 1/12.
  const std::vector<double> gaussian = variances(1.5, 0.0);
  EXPECT_NEAR(gaussian[0], gaussian[1], 0.2);
  EXPECT_NEAR(gaussian[0], 2.33, 0.2);
}

TEST(VideoArtifacts, CompressionChangesPixelsButKeepsAPlausiblePsnrAndTheFrameCount)
{
  // A smooth random texture drifting 2 px per frame, as a slow scope's view.
  cv::Mat texture(300, 400, CV_8UC3);
  cv::randu(texture, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.5);
  cv::normalize(texture, texture, 20, 235, cv::NORM_MINMAX);
  std::vector<cv::Mat> frames;
  for (int f = 0; f < 12; ++f)
  {
    frames.push_back(texture(cv::Rect(2 * f, f, 320, 240)).clone());
  }
  double lowQuality = 0.0;
  double highQuality = 0.0;
  for (const auto& [codec, quality] : std::vector<std::pair<VideoCompression, int>>{
         { VideoCompression::Mjpg, 20 }, { VideoCompression::Mjpg, 95 },
         { VideoCompression::H264, 0 }, { VideoCompression::Mp4v, 0 } })
  {
    const std::string name = videoCompressionName(codec) + " " + std::to_string(quality);
    const std::vector<cv::Mat> decoded = compressVideo(frames, codec, quality, 30.0);
    ASSERT_EQ(decoded.size(), frames.size()) << name;
    double psnr = 0.0;
    for (size_t f = 0; f < frames.size(); ++f)
    {
      ASSERT_EQ(decoded[f].size(), frames[f].size()) << name;
      ASSERT_EQ(decoded[f].type(), CV_8UC3) << name;
      EXPECT_GT(cv::norm(decoded[f], frames[f], cv::NORM_INF), 0.0) << name << " frame " << f;
      psnr += cv::PSNR(decoded[f], frames[f]) / frames.size();
    }
    EXPECT_GT(psnr, 25.0) << name;
    EXPECT_LT(psnr, 50.0) << name;
    if (codec == VideoCompression::Mjpg)
    {
      (quality == 20 ? lowQuality : highQuality) = psnr;
    }
  }
  EXPECT_LT(lowQuality + 2.0, highQuality);
  EXPECT_EQ(compressVideo(frames, VideoCompression::None, 0, 30.0)[3].data, frames[3].data);
}

TEST(VideoArtifacts, OccludersCoverAboutTheRequestedAreaOfTheRequestedFractionOfFrames)
{
  const std::vector<bool> chosen = occludedFrames(40, 0.25, 3);
  EXPECT_EQ(std::count(chosen.begin(), chosen.end(), true), 10);
  EXPECT_EQ(occludedFrames(40, 0.25, 3), chosen);
  EXPECT_NE(occludedFrames(40, 0.25, 4), chosen);
  const std::vector<bool> none = occludedFrames(40, 0.0, 3);
  EXPECT_EQ(std::count(none.begin(), none.end(), true), 0);
  for (std::uint64_t seed = 1; seed <= 5; ++seed)
  {
    for (const double area : { 0.05, 0.2, 0.5 })
    {
      const cv::Mat coverage = occluderCoverage(320, 240, area, seed);
      const double covered = cv::countNonZero(coverage >= 0.5f) / 76800.0;
      EXPECT_NEAR(covered, area, 0.01) << "seed " << seed << ", area " << area;
      // Smooth: soft edges between the clear and the covered.
      EXPECT_GT(cv::countNonZero((coverage > 0.05f) & (coverage < 0.95f)), 0);
      cv::Mat light(240, 320, CV_32FC3, cv::Scalar(150.0, 160.0, 170.0));
      applyOccluders(light, coverage, 0.8);
      int darkRed = 0;
      for (int v = 0; v < 240; ++v)
      {
        for (int u = 0; u < 320; ++u)
        {
          const cv::Vec3f p = light.at<cv::Vec3f>(v, u);
          darkRed += p[2] < 120.0f && p[2] > p[0] + 30.0f && p[2] > p[1] + 30.0f;
        }
      }
      EXPECT_NEAR(darkRed / 76800.0, area, 0.5 * area) << "seed " << seed << ", area " << area;
    }
  }
}

TEST(VideoArtifacts, ValidateNamesTheKnobAndItsBadValue)
{
  auto message = [](const std::function<void(VideoArtifactOptions&)>& set)
  {
    VideoArtifactOptions o;
    set(o);
    return messageOf([&o] { o.validate(); });
  };
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.exposureTimeS = -0.01; }),
    "the exposure time must lie in [0, 1] s, not -0.01");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.exposureTimeS = std::nan(""); }),
    "the exposure time must lie in [0, 1] s, not nan");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.motionBlurSamples = 1; }),
    "the motion blur's number of samples must lie in [2, 64], not 1");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.specularStrength = -1.0; }),
    "the specular highlights' strength must lie in [0, 10], not -1");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.specularAngleDeg = 0.0; }),
    "the specular highlights' angle must lie in (0, 45] degrees, not 0");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.exposureGain = 0.0; }),
    "the exposure gain must lie in (0, 10], not 0");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.shotNoise = 20.0; }),
    "the shot noise must lie in [0, 10] grey levels per electron, not 20");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.compressionQuality = 101; }),
    "the compression quality must lie in [1, 100] (0: the writer's own), not 101");
  EXPECT_EQ(message(
              [](VideoArtifactOptions& o)
              {
                o.compression = VideoCompression::H264;
                o.compressionQuality = 50;
              }),
    "the compression quality applies to mjpg only: OpenCV's FFmpeg writer of h264 has no quality "
    "setting");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.occludedFrameFraction = 1.5; }),
    "the fraction of occluded frames must lie in [0, 1], not 1.5");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.occluderAreaFraction = 0.95; }),
    "the occluders' area fraction must lie in (0, 0.9], not 0.95");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.occluderOpacity = 0.0; }),
    "the occluders' opacity must lie in (0, 1], not 0");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.wallContactFraction = 0.6; }),
    "the fraction of frames in wall contact must lie in [0, 0.5], not 0.6");
  EXPECT_EQ(message([](VideoArtifactOptions& o) { o.wallContactFrames = 0; }),
    "a stretch of wall contact must last 1 to 300 frames, not 0");
}

TEST(VideoArtifacts, WallContactComesInSeparateStretchesOfTheRequestedLength)
{
  const std::vector<bool> touching = wallContactFrames(600, 0.05, 10, 3);
  EXPECT_EQ(std::count(touching.begin(), touching.end(), true), 30);
  EXPECT_FALSE(touching[0]);
  // Three stretches of 10 frames, apart from one another.
  std::vector<int> lengths;
  for (std::size_t f = 0; f < touching.size(); ++f)
  {
    if (touching[f] && (f == 0 || !touching[f - 1]))
    {
      lengths.push_back(0);
    }
    if (touching[f])
    {
      ++lengths.back();
    }
  }
  EXPECT_EQ(lengths, std::vector<int>({ 10, 10, 10 }));
  EXPECT_EQ(wallContactFrames(600, 0.05, 10, 3), touching);
  EXPECT_NE(wallContactFrames(600, 0.05, 10, 4), touching);
  const std::vector<bool> none = wallContactFrames(600, 0.0, 10, 3);
  EXPECT_EQ(std::count(none.begin(), none.end(), true), 0);
}

TEST(VideoArtifacts, WallContactLeavesARedBlurWithoutCorners)
{
  // A textured picture (a checkerboard of 8 px squares) pressed on the lens:
  // red above green above blue, and no corner left to track.
  cv::Mat light(240, 320, CV_32FC3);
  for (int v = 0; v < light.rows; ++v)
  {
    for (int u = 0; u < light.cols; ++u)
    {
      const float value = ((u / 8 + v / 8) % 2) ? 200.0f : 40.0f;
      light.at<cv::Vec3f>(v, u) = cv::Vec3f(value, value, value);
    }
  }
  const auto corners = [](const cv::Mat& picture)
  {
    cv::Mat grey;
    cv::cvtColor(picture, grey, cv::COLOR_BGR2GRAY);
    cv::Mat eight;
    grey.convertTo(eight, CV_8U);
    std::vector<cv::Point2f> found;
    cv::goodFeaturesToTrack(eight, found, 300, 0.01, 5.0);
    return found.size();
  };
  EXPECT_GT(corners(light), 100u);
  applyWallContact(light);
  const cv::Scalar mean = cv::mean(light);
  EXPECT_NEAR(mean[2], 1.5 * 120.0, 1.0);
  EXPECT_NEAR(mean[1], 0.4 * mean[2], 1.0);
  EXPECT_NEAR(mean[0], 0.2 * mean[2], 1.0);
  EXPECT_EQ(corners(light), 0u);
}
