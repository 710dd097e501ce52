#include <vimlop/Core/Error.h>
#include <vimlop/Video/StructureFromMotion.h>

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

using namespace vimlop;

namespace
{

PinholeCamera camera(int width = 320, int height = 240)
{
  PinholeCamera k;
  k.fx = k.fy = 200.0;
  k.cx = 0.5 * (width - 1);
  k.cy = 0.5 * (height - 1);
  k.widthPx = width;
  k.heightPx = height;
  return k;
}

/// Blobby random texture, the same for a given seed.
cv::Mat texture(int seed, int width = 320, int height = 240)
{
  cv::RNG rng(static_cast<uint64_t>(seed));
  cv::Mat noise(height, width, CV_32F);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
  cv::normalize(noise, noise, 20, 235, cv::NORM_MINMAX);
  cv::Mat grey;
  noise.convertTo(grey, CV_8U);
  cv::Mat bgr;
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

std::string messageOf(const std::vector<cv::Mat>& frames, const PinholeCamera& k)
{
  try
  {
    StructureFromMotion().reconstruct(frames, k);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(StructureFromMotion, NeedsTwoFramesOfOneSizeMatchingTheIntrinsics)
{
  EXPECT_EQ(messageOf({ texture(1) }, camera()), "SfM needs at least 2 frames, got 1");
  EXPECT_EQ(messageOf({ texture(1), texture(2, 160, 120) }, camera()),
    "SfM: frame 'frame1' is 160x120 but 'frame0' is 320x240");
  EXPECT_EQ(messageOf({ texture(1), texture(2) }, camera(640, 480)),
    "SfM: the intrinsics are for 640x480 pixels but the frames are 320x240");
  EXPECT_EQ(messageOf({ texture(1), cv::Mat(240, 320, CV_16UC3) }, camera()),
    "SfM: frame 'frame1' is not an 8-bit grey or colour image");
}

TEST(StructureFromMotion, CannotInitialiseWithoutTexture)
{
  const std::vector<cv::Mat> flat(5, cv::Mat(240, 320, CV_8UC3, cv::Scalar(90, 100, 180)));
  EXPECT_EQ(messageOf(flat, camera()),
    "SfM cannot initialise: the frames have too little texture (median 0 SIFT features per frame; "
    "at least 40 needed in two frames)");
}

TEST(StructureFromMotion, CannotInitialiseWithoutMotion)
{
  const cv::Mat frame = texture(3);
  const std::vector<cv::Mat> still = { frame, frame.clone(), frame.clone(), frame.clone() };
  EXPECT_EQ(messageOf(still, camera()),
    "SfM cannot initialise: the camera hardly moves (features move by at most 0.00 px between the "
    "frames compared, at least 0.50 px needed)");
}

TEST(StructureFromMotion, FindsNoFeatureOutsideTheFeatureMask)
{
  // Textured frames that do not move: with every pixel valid SfM finds the
  // features and fails only for want of motion; with a mask that excludes
  // every pixel it finds none.
  const cv::Mat frame = texture(4);
  const std::vector<cv::Mat> still = { frame, frame.clone(), frame.clone() };
  StructureFromMotion masked;
  masked.setFeatureMask(cv::Mat(240, 320, CV_8U, cv::Scalar(0)));
  std::string message = "no error";
  try
  {
    masked.reconstruct(still, camera());
  }
  catch (const Error& e)
  {
    message = e.what();
  }
  EXPECT_NE(message.find("too little texture (median 0 SIFT features"), std::string::npos)
    << message;
  EXPECT_NE(messageOf(still, camera()).find("the camera hardly moves"), std::string::npos);

  masked.setFeatureMask(cv::Mat(10, 10, CV_8U, cv::Scalar(255)));
  message = "no error";
  try
  {
    masked.reconstruct(still, camera());
  }
  catch (const Error& e)
  {
    message = e.what();
  }
  EXPECT_EQ(
    message, "SfM: the feature mask must be an 8-bit single-channel image of the frames' size");
}
