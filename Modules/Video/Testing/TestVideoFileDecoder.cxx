#include <vimlop/Core/Error.h>
#include <vimlop/Video/FrameSequence.h>
#include <vimlop/Video/FrameStream.h>
#include <vimlop/Video/VideoFileDecoder.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <opencv2/videoio.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

using namespace vimlop;

namespace
{

namespace fs = std::filesystem;

/// A stand-in for ffmpeg in `dir`: a shell script that ignores its arguments.
std::string fakeDecoder(const fs::path& dir, const std::string& name, const std::string& script)
{
  const fs::path path = dir / name;
  std::ofstream(path) << "#!/bin/sh\n" << script << "\n";
  fs::permissions(path, fs::perms::owner_all);
  return path.string();
}

/// A video file for the fake decoders (they never read it).
std::string anyVideo(const fs::path& dir)
{
  const fs::path path = dir / "any.avi";
  std::ofstream(path) << "frames";
  return path.string();
}

std::string messageOf(
  const std::string& video, const std::string& program, double idleTimeoutS = 10.0)
{
  return fixtures::errorMessageOf(
    [&]
    {
      detail::decodeVideoFile(
        video, 8, program, [](int, std::uint64_t, std::uint64_t) {}, idleTimeoutS);
    });
}

/// Two frames of 2 x 1 pixels: red, then blue.
const char* const twoFrames =
  "printf 'P6\\n2 1\\n255\\n\\377\\0\\0\\377\\0\\0'; printf 'P6 2 1 255 \\0\\0\\377\\0\\0\\377'";

} // namespace

TEST(VideoFileDecoder, ReadsTheDecodersFramesAsBGRAndStopsItWhenItHasEnough)
{
  const fs::path dir = fixtures::freshTestFolder("video-decoder");
  std::vector<std::string> sizes;
  const std::vector<cv::Mat> frames =
    detail::decodeVideoFile(anyVideo(dir), 8, fakeDecoder(dir, "two-frames", twoFrames),
      [&](int i, std::uint64_t w, std::uint64_t h)
      { sizes.push_back(std::to_string(i) + ":" + std::to_string(w) + "x" + std::to_string(h)); });
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(sizes, (std::vector<std::string>{ "0:2x1", "1:2x1" }));
  EXPECT_EQ(frames[0].at<cv::Vec3b>(0, 1), cv::Vec3b(0, 0, 255)); // red, in BGR
  EXPECT_EQ(frames[1].at<cv::Vec3b>(0, 0), cv::Vec3b(255, 0, 0)); // blue
  // As many frames as asked for: the decoder is stopped, not waited for.
  const std::string endless = fakeDecoder(dir, "endless", std::string(twoFrames) + "; sleep 30");
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(
    detail::decodeVideoFile(anyVideo(dir), 2, endless, [](int, std::uint64_t, std::uint64_t) {})
      .size(),
    2u);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(VideoFileDecoder, ADecoderThatCrashesOrStopsMidFrameIsAMessageNotACrash)
{
  const fs::path dir = fixtures::freshTestFolder("video-decoder");
  const std::string video = anyVideo(dir);
  EXPECT_EQ(
    messageOf(video,
      fakeDecoder(dir, "crashes",
        "printf 'P6\\n2 1\\n255\\n\\1\\2\\3\\4\\5\\6'; echo 'broken stream' >&2; kill -SEGV $$")),
    "'" + video +
      "': the video decoder failed after 1 frame (crashes was killed by signal 11, saying: "
      "broken stream)");
  EXPECT_EQ(messageOf(video, fakeDecoder(dir, "mid-frame", "printf 'P6\\n2 1\\n255\\n\\1\\2\\3'")),
    "'" + video + "': the video decoder stopped inside frame 0 (3 of its 6 bytes)");
  EXPECT_EQ(messageOf(video, fakeDecoder(dir, "not-ppm", "printf 'GIF89a'")),
    "'" + video + "': the video decoder's output is not an 8-bit PPM image at frame 0");
  EXPECT_EQ(messageOf(video, fakeDecoder(dir, "16-bit", "printf 'P6\\n2 1\\n65535\\n'")),
    "'" + video + "': the video decoder's output is not an 8-bit PPM image at frame 0");
  EXPECT_EQ(messageOf(video, fakeDecoder(dir, "fails", "echo 'moov atom not found' >&2; exit 1")),
    "'" + video + "': not a readable video file (fails: moov atom not found)");
  EXPECT_EQ(messageOf(video, fakeDecoder(dir, "silent-fail", "exit 3")),
    "'" + video + "': not a readable video file (silent-fail failed with exit code 3)");
  EXPECT_EQ(messageOf(video, fakeDecoder(dir, "no-frames", "exit 0")),
    "'" + video + "': the video has no readable frames");
  const std::string hangs = fakeDecoder(dir, "hangs", "sleep 30");
  EXPECT_EQ(messageOf(video, hangs, 0.2),
    "'" + video + "': the video decoder stopped answering: '" + hangs +
      "': sent nothing for 0.2 s");
}

TEST(VideoFileDecoder, AFrameTooLargeIsRefusedFromItsHeaderBeforeItsPixels)
{
  const fs::path dir = fixtures::freshTestFolder("video-decoder");
  // The fake sends a header only: reading the 30 GB it announces would hang.
  ::setenv("VIMLOP_FFMPEG",
    fakeDecoder(dir, "huge", "printf 'P6\\n100000 100000\\n255\\n'; sleep 30").c_str(), 1);
  const std::string video = anyVideo(dir);
  EXPECT_EQ(fixtures::errorMessageOf([&] { FrameSequence::load(video); }),
    "'" + video +
      "': frame 'frame0' is 100000 x 100000 pixels; frames of at most 67108864 pixels (8192 x "
      "8192) are read");
  ::setenv("VIMLOP_FFMPEG", "/no/such/ffmpeg", 1);
  const std::string missing = fixtures::errorMessageOf([&] { FrameSequence::load(video); });
  ::unsetenv("VIMLOP_FFMPEG");
  EXPECT_EQ(missing,
    "'" + video +
      "': a video file is decoded by FFmpeg's 'ffmpeg' program (Debian package 'ffmpeg', or "
      "$VIMLOP_FFMPEG), which cannot be run here: '/no/such/ffmpeg': cannot start it (No such "
      "file or directory); or give a folder of frame images");
}

TEST(VideoFileDecoder, TheRealDecoderReadsOnlyLocalFilesAndTheFirstVideoStream)
{
  const std::vector<std::string> arguments =
    detail::videoDecoderArguments("ffmpeg", "clip.mp4", 30);
  const auto after = [&](const std::string& option)
  {
    const auto at = std::find(arguments.begin(), arguments.end(), option);
    return at == arguments.end() || at + 1 == arguments.end() ? std::string() : *(at + 1);
  };
  EXPECT_EQ(after("-protocol_whitelist"), "file");
  EXPECT_EQ(after("-i"), "file:" + (fs::current_path() / "clip.mp4").string());
  EXPECT_EQ(after("-map"), "0:v:0");
  EXPECT_EQ(after("-frames:v"), "30");
  EXPECT_EQ(after("-c:v"), "ppm");
  EXPECT_EQ(after("-pix_fmt"), "rgb24");
  EXPECT_EQ(arguments.back(), "pipe:1");
}

TEST(VideoFileDecoder, AStreamedVideoGivesItsFramesBeforeTheDecodersFailureIsTold)
{
  const fs::path dir = fixtures::freshTestFolder("video-decoder");
  ::setenv("VIMLOP_FFMPEG",
    fakeDecoder(dir, "fails-late", std::string(twoFrames) + "; echo 'corrupt packet' >&2; exit 1")
      .c_str(),
    1);
  const std::string video = anyVideo(dir);
  FrameStream stream = FrameStream::open(video);
  ::unsetenv("VIMLOP_FFMPEG");
  EXPECT_EQ(stream.indexOfName("frame1"), 1);
  StreamedFrame f;
  ASSERT_TRUE(stream.next(f));
  EXPECT_EQ(f.name, "frame0");
  ASSERT_TRUE(stream.next(f));
  EXPECT_EQ(f.id, 1);
  EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0), cv::Vec3b(255, 0, 0));
  EXPECT_EQ(fixtures::errorMessageOf([&] { stream.next(f); }),
    "'" + video + "': the video decoder failed after 2 frames (fails-late: corrupt packet)");
  EXPECT_FALSE(stream.next(f));
}
