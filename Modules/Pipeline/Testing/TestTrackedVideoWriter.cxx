#include <vimlop/Pipeline/TrackedVideoWriter.h>

#include <vimlop/Core/VisibleModelContours.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include "ErrorMessage.h"
#include "TestFolders.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <opencv2/videoio.hpp>

#include <cmath>
#include <filesystem>

namespace vimlop
{
namespace
{

TEST(TrackedVideoWriter, DrawsTheContoursTheCameraSeesUnderABandInTheStatesColour)
{
  const std::filesystem::path dir = fixtures::freshTestFolder("tracked-video");
  const TriangleMesh tube = fixtures::makeTube(4.0, 60.0, 0.35);
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  const std::string path = (dir / "tracked.avi").string();
  const cv::Mat grey(k.heightPx, k.widthPx, CV_8UC3, cv::Scalar(60, 60, 60));
  const std::vector<ModelContourPoint> seen =
    visibleModelContours(makeEmbreeRegistrationModel(tube), k, fixtures::cameraOnTheTubeAxis());
  ASSERT_GT(seen.size(), 50u);
  {
    TrackedVideoWriter writer(k, path, 30.0);
    TrackedFrame t;
    t.cameraToCT = fixtures::cameraOnTheTubeAxis();
    const cv::Mat tracking = writer.write(grey, t, "frame0", seen, 1.25);
    ASSERT_EQ(tracking.size(), cv::Size(k.widthPx, k.heightPx + 30));
    // Green band; each contour sample a green dot where the camera sees it.
    EXPECT_EQ(tracking.at<cv::Vec3b>(2, 2), cv::Vec3b(46, 122, 27));
    for (std::size_t i = 0; i < seen.size(); i += 10)
    {
      const cv::Point at(static_cast<int>(std::lround(seen[i].pixel.x())),
        static_cast<int>(std::lround(seen[i].pixel.y())) + 30);
      EXPECT_EQ(tracking.at<cv::Vec3b>(at), cv::Vec3b(80, 255, 80)) << at;
    }
    // Below the band, nothing else changed: the picture is the frame where no contour is.
    EXPECT_EQ(tracking.at<cv::Vec3b>(k.heightPx + 29, 0), cv::Vec3b(60, 60, 60));
    t.state = TrackingState::Lost;
    t.reason = "no pose agrees with 3 tracked features";
    EXPECT_EQ(writer.write(grey, t, "frame1", seen, std::nan("")).at<cv::Vec3b>(2, 2),
      cv::Vec3b(27, 22, 179));
    t.state = TrackingState::Degraded;
    EXPECT_EQ(writer.write(grey, t, "frame2", {}, 3.0).at<cv::Vec3b>(2, 2), cv::Vec3b(0, 98, 122));
    EXPECT_EQ(writer.framesWritten(), 3);
    EXPECT_EQ(
      fixtures::errorMessageOf([&] { writer.write(cv::Mat(10, 10, CV_8UC3), t, "x", seen, 1.0); }),
      "tracked video: a frame of 10 x 10 pixels (type 16), but the camera is 320 x 240 and frames "
      "are 8-bit BGR");
  }
  cv::VideoCapture video(path);
  ASSERT_TRUE(video.isOpened());
  int frames = 0;
  for (cv::Mat f; video.read(f); ++frames)
  {
    EXPECT_EQ(f.size(), cv::Size(k.widthPx, k.heightPx + 30));
  }
  EXPECT_EQ(frames, 3);
  EXPECT_EQ(fixtures::errorMessageOf([&] { TrackedVideoWriter(k, path, 0.0); }),
    "tracked video: the rate must be positive, not 0 fps");
}

} // namespace
} // namespace vimlop
