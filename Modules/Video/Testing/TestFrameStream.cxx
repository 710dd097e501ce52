#include <vimlop/Video/FrameStream.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>

using namespace vimlop;

namespace
{

namespace fs = std::filesystem;

/// A 4 x 3 frame whose pixels all have the value `v`.
void writeFrame(const fs::path& file, int v, cv::Size size = cv::Size(4, 3))
{
  cv::imwrite(file.string(), cv::Mat(size, CV_8UC3, cv::Scalar(v, v, v)));
}

} // namespace

TEST(FrameStream, GivesAFoldersFramesOneAtATimeInNaturalOrderWithTheirNumbersAsIds)
{
  const fs::path dir = fixtures::freshTestFolder("frame-stream");
  writeFrame(dir / "frame10.png", 10);
  writeFrame(dir / "frame2.png", 2);
  writeFrame(dir / "frame3.png", 3);
  FrameStream stream = FrameStream::open(dir.string());
  EXPECT_EQ(stream.indexOfName("frame10.png"), 2);
  EXPECT_EQ(stream.indexOfName("frame4.png"), std::nullopt);
  StreamedFrame f;
  std::vector<std::string> got;
  while (stream.next(f))
  {
    EXPECT_EQ(f.image.type(), CV_8UC3);
    EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], f.id) << f.name;
    EXPECT_FALSE(f.timestampS.has_value()) << "a folder records no time";
    got.push_back(f.name + ":" + std::to_string(f.id) + "@" + std::to_string(f.index));
  }
  EXPECT_EQ(
    got, (std::vector<std::string>{ "frame2.png:2@0", "frame3.png:3@1", "frame10.png:10@2" }));
  EXPECT_FALSE(stream.next(f));
}

TEST(FrameStream, AnUnreadableFrameMidwayIsAnErrorNamingItAfterTheFramesBeforeIt)
{
  const fs::path dir = fixtures::freshTestFolder("frame-stream");
  writeFrame(dir / "frame1.png", 1);
  writeFrame(dir / "frame2.png", 2);
  std::ofstream(dir / "frame3.png") << "not a picture";
  writeFrame(dir / "frame4.png", 4, cv::Size(8, 6));
  FrameStream stream = FrameStream::open(dir.string());
  StreamedFrame f;
  ASSERT_TRUE(stream.next(f));
  ASSERT_TRUE(stream.next(f));
  EXPECT_EQ(f.id, 2);
  EXPECT_EQ(fixtures::errorMessageOf([&] { stream.next(f); }),
    "'" + (dir / "frame3.png").string() + "': not a readable image");
  // The stream goes on past it when asked; a frame of another size is refused.
  EXPECT_EQ(fixtures::errorMessageOf([&] { stream.next(f); }),
    "'" + dir.string() + "': frame 'frame4.png' is 8x6 but the first frame is 4x3");
}

TEST(FrameStream, RefusesAMissingPathAnEmptyFolderAndACameraThatIsNotThere)
{
  const fs::path dir = fixtures::freshTestFolder("frame-stream");
  EXPECT_EQ(fixtures::errorMessageOf([&] { FrameStream::open((dir / "none").string()); }),
    "'" + (dir / "none").string() + "': no such file or folder");
  EXPECT_EQ(fixtures::errorMessageOf([&] { FrameStream::open(dir.string()); }),
    "'" + dir.string() +
      "': the folder holds no image files (.png, .jpg, .jpeg, .bmp, .tif, .tiff)");
  EXPECT_EQ(fixtures::errorMessageOf([&] { FrameStream::openCamera(97); }),
    "camera 97 (/dev/video97): no such camera device on this machine");
}
