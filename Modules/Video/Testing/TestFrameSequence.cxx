#include <vimlop/Core/Error.h>
#include <vimlop/Video/FrameSequence.h>
#include <vimlop/Video/ImageFileHeader.h>

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include <filesystem>
#include <fstream>

using namespace vimlop;
namespace fs = std::filesystem;

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;

/// A frame whose top-left pixel encodes its index.
cv::Mat numberedFrame(int index, int width = 64, int height = 48)
{
  cv::Mat frame(height, width, CV_8UC3, cv::Scalar(20, 40, 60));
  frame.at<cv::Vec3b>(0, 0) = cv::Vec3b(static_cast<uchar>(10 * index), 0, 0);
  return frame;
}

std::string freshFolder(const std::string& name)
{
  const std::string folder = out + "/" + name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

std::string messageOf(const std::string& path)
{
  try
  {
    FrameSequence::load(path);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(FrameSequence, LoadsAFolderInNaturalOrder)
{
  const std::string folder = freshFolder("frames");
  // Written out of order, with names that sort wrongly as plain strings.
  for (int i : { 10, 2, 1, 0, 11 })
  {
    cv::imwrite(folder + "/frame" + std::to_string(i) + ".png", numberedFrame(i));
  }
  std::ofstream(folder + "/notes.txt") << "not a frame";
  const FrameSequence sequence = FrameSequence::load(folder);
  ASSERT_EQ(sequence.size(), 5);
  const int expected[] = { 0, 1, 2, 10, 11 };
  for (int k = 0; k < 5; ++k)
  {
    EXPECT_EQ(sequence.frame(k).at<cv::Vec3b>(0, 0)[0], 10 * expected[k]) << k;
    EXPECT_EQ(sequence.name(k), "frame" + std::to_string(expected[k]) + ".png");
  }
  EXPECT_EQ(sequence.names(),
    std::vector<std::string>(
      { "frame0.png", "frame1.png", "frame2.png", "frame10.png", "frame11.png" }));
  EXPECT_EQ(sequence.widthPx(), 64);
  EXPECT_EQ(sequence.heightPx(), 48);
  EXPECT_EQ(FrameSequence::load(folder, 2).size(), 2);
}

TEST(FrameSequence, GreyFramesBecomeBGR)
{
  const std::string folder = freshFolder("grey");
  cv::imwrite(folder + "/a.png", cv::Mat(10, 12, CV_8UC1, cv::Scalar(77)));
  const FrameSequence sequence = FrameSequence::load(folder);
  EXPECT_EQ(sequence.frame(0).type(), CV_8UC3);
  EXPECT_EQ(sequence.frame(0).at<cv::Vec3b>(5, 5), cv::Vec3b(77, 77, 77));
}

TEST(FrameSequence, LoadsAVideoFile)
{
  const std::string path = out + "/clip.avi";
  cv::VideoWriter writer(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10.0, cv::Size(64, 48));
  ASSERT_TRUE(writer.isOpened()) << "OpenCV cannot write MJPG here";
  for (int i = 0; i < 7; ++i)
  {
    writer.write(numberedFrame(i));
  }
  writer.release();
  const FrameSequence sequence = FrameSequence::load(path);
  EXPECT_EQ(sequence.size(), 7);
  EXPECT_EQ(sequence.name(3), "frame3");
  EXPECT_EQ(sequence.ids(), (std::vector<int>{ 0, 1, 2, 3, 4, 5, 6 }));
  EXPECT_EQ(sequence.widthPx(), 64);
  EXPECT_DOUBLE_EQ(sequence.framesPerSecond(), 10.0) << "the stream's rate, read by ffprobe";
  EXPECT_TRUE(sequence.timestampsS().empty());
}

TEST(FrameSequence, AVideoWhoseRateCannotBeReadRecordsNone)
{
  const std::string path = out + "/clip-rate.avi";
  cv::VideoWriter writer(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25.0, cv::Size(64, 48));
  ASSERT_TRUE(writer.isOpened()) << "OpenCV cannot write MJPG here";
  for (int i = 0; i < 3; ++i)
  {
    writer.write(numberedFrame(i));
  }
  writer.release();
  EXPECT_DOUBLE_EQ(FrameSequence::load(path).framesPerSecond(), 25.0);
  ::setenv("VIMLOP_FFPROBE", "/no/such/ffprobe", 1);
  const FrameSequence sequence = FrameSequence::load(path);
  ::unsetenv("VIMLOP_FFPROBE");
  EXPECT_EQ(sequence.size(), 3) << "the frames do not depend on the rate";
  EXPECT_EQ(sequence.framesPerSecond(), 0.0);
}

TEST(FrameSequence, ErrorsNameThePathAndTheProblem)
{
  EXPECT_EQ(
    messageOf(out + "/no-such-folder"), "'" + out + "/no-such-folder': no such file or folder");
  const std::string empty = freshFolder("noframes");
  EXPECT_EQ(messageOf(empty),
    "'" + empty + "': the folder holds no image files (.png, .jpg, .jpeg, .bmp, .tif, .tiff)");
  const std::string mixed = freshFolder("mixedsizes");
  cv::imwrite(mixed + "/0.png", numberedFrame(0, 64, 48));
  cv::imwrite(mixed + "/1.png", numberedFrame(1, 32, 48));
  EXPECT_EQ(messageOf(mixed), "'" + mixed + "': frame '1.png' is 32x48 but '0.png' is 64x48");
  const std::string broken = freshFolder("brokenframe");
  std::ofstream(broken + "/0.png") << "not a png";
  EXPECT_EQ(messageOf(broken), "'" + broken + "/0.png': not a readable image");
  std::ofstream(out + "/movie.mp4") << "not a movie";
  EXPECT_EQ(messageOf(out + "/movie.mp4"),
    "'" + out +
      "/movie.mp4': not a readable video file (ffmpeg: Invalid data found when "
      "processing input)");
}

namespace
{

/// A copy of a real PNG whose IHDR claims another size: its pixels are never
/// decoded when the claim is refused (the CRC no longer matches either).
void writePngClaiming(const std::string& path, std::uint32_t width, std::uint32_t height)
{
  std::vector<uchar> bytes;
  cv::imencode(".png", numberedFrame(0, 8, 8), bytes);
  for (int i = 0; i < 4; ++i)
  {
    bytes[16 + i] = static_cast<uchar>(width >> (24 - 8 * i));
    bytes[20 + i] = static_cast<uchar>(height >> (24 - 8 * i));
  }
  std::ofstream(path, std::ios::binary)
    .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

} // namespace

TEST(FrameSequence, HeadersGiveTheSizeOfPngJpegAndBmpFramesWithoutDecoding)
{
  const std::string folder = freshFolder("headers");
  for (const char* extension : { ".png", ".jpg", ".bmp" })
  {
    const std::string file = folder + "/frame" + extension;
    cv::imwrite(file, numberedFrame(1, 75, 33));
    const ImageFileHeader header = readImageFileHeader(file);
    EXPECT_TRUE(header.known) << extension;
    EXPECT_EQ(header.widthPx, 75u) << extension;
    EXPECT_EQ(header.heightPx, 33u) << extension;
  }
  cv::imwrite(folder + "/frame.tif", numberedFrame(1, 75, 33));
  EXPECT_FALSE(readImageFileHeader(folder + "/frame.tif").known);
  std::ofstream(folder + "/short.png") << "\x89PNG";
  EXPECT_FALSE(readImageFileHeader(folder + "/short.png").known);
}

TEST(FrameSequence, AFrameThatWouldDecodeToGigabytesIsRefusedBeforeDecoding)
{
  // The 380 KB PNG of 2 GB: a header is all it takes.
  const std::string bomb = freshFolder("bomb");
  cv::imwrite(bomb + "/0.png", numberedFrame(0));
  writePngClaiming(bomb + "/1.png", 40000, 40000);
  EXPECT_EQ(messageOf(bomb),
    "'" + bomb +
      "': frame '1.png' is 40000 x 40000 pixels; frames of at most 67108864 pixels (8192 x "
      "8192) are read");
  // 45 frames of 8000 x 8000 take 45 x 192 MB, past the 8 GiB budget: the
  // 45th header stops it before any decoding (the pixel data are an 8 x 8
  // frame's, so decoding the first file would have failed with another message).
  const std::string many = freshFolder("manylarge");
  for (int i = 0; i < 46; ++i)
  {
    writePngClaiming(many + "/" + std::to_string(i) + ".png", 8000, 8000);
  }
  EXPECT_EQ(messageOf(many),
    "'" + many +
      "': the first 45 frames of 8000 x 8000 pixels would take more than 8 GiB decoded; read "
      "fewer (--max-frames)");
}

TEST(FrameSequence, AFrameKeepsTheNumberOfItsFileAsItsIdSoAMissingFileIsAGap)
{
  const std::string folder = freshFolder("numbered");
  for (int i : { 8, 9, 11, 12, 15 })
  {
    char name[32];
    std::snprintf(name, sizeof name, "/frame%03d.png", i);
    cv::imwrite(folder + name, numberedFrame(i));
  }
  const FrameSequence sequence = FrameSequence::load(folder);
  EXPECT_EQ(sequence.ids(), (std::vector<int>{ 8, 9, 11, 12, 15 }));
  EXPECT_EQ(sequence.idGaps(),
    "frame 10 (between 'frame009.png' and 'frame011.png'), frames 13 to 14 (between "
    "'frame012.png' and 'frame015.png')");
  EXPECT_EQ(FrameSequence::load(folder, 2).idGaps(), "");
}

TEST(FrameSequence, NamesThatDoNotNumberTheFramesGiveTheirIndices)
{
  // No number in one name, two names with one number, a video: indices.
  const std::string unnumbered = freshFolder("unnumbered");
  cv::imwrite(unnumbered + "/a1.png", numberedFrame(0));
  cv::imwrite(unnumbered + "/b.png", numberedFrame(1));
  EXPECT_EQ(FrameSequence::load(unnumbered).ids(), (std::vector<int>{ 0, 1 }));
  const std::string stereo = freshFolder("stereo");
  cv::imwrite(stereo + "/left7.png", numberedFrame(0));
  cv::imwrite(stereo + "/right7.png", numberedFrame(1));
  EXPECT_EQ(FrameSequence::load(stereo).ids(), (std::vector<int>{ 0, 1 }));
  EXPECT_EQ(FrameSequence::load(stereo).idGaps(), "");
  const std::string huge = freshFolder("hugenumber");
  cv::imwrite(huge + "/frame99999999999.png", numberedFrame(0));
  EXPECT_EQ(FrameSequence::load(huge).ids(), (std::vector<int>{ 0 }));
}

TEST(FrameSequence, AFrameOpenCVThrowsOnIsRefusedWithItsReason)
{
  // A TIFF (whose header VIMLOP does not read) of 40000 x 40000 pixels:
  // OpenCV's decoder throws at its own limit of 2^30 pixels.
  std::string tiff("II*\0\x08\0\0\0", 8);
  const auto u16 = [&](std::uint16_t v) { tiff.append(reinterpret_cast<const char*>(&v), 2); };
  const auto u32 = [&](std::uint32_t v) { tiff.append(reinterpret_cast<const char*>(&v), 4); };
  const auto entry = [&](std::uint16_t tag, std::uint16_t type, std::uint32_t value)
  {
    u16(tag);
    u16(type);
    u32(1);
    u32(value);
  };
  u16(6);
  entry(256, 4, 40000); // ImageWidth
  entry(257, 4, 40000); // ImageLength
  entry(258, 3, 8);     // BitsPerSample
  entry(262, 3, 1);     // Photometric: black is zero
  entry(273, 4, 200);   // StripOffsets
  entry(279, 4, 16);    // StripByteCounts
  u32(0);
  tiff.resize(216, '\0');
  const std::string folder = freshFolder("huge-tiff");
  std::ofstream(folder + "/0.tif", std::ios::binary) << tiff;
  const std::string message = messageOf(folder);
  EXPECT_EQ(message,
    "'" + folder + "/0.tif': not a readable image (OpenCV: pixels <= CV_IO_MAX_IMAGE_PIXELS)");
}
