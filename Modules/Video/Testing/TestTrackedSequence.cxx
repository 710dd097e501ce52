// Tracked image sequences as PLUS and 3D Slicer record them (.igs.mha): the
// frames with their timestamps, the tracker from one of their transforms, and
// the frames' times on the tracker's clock.

#include <vimlop/Core/Error.h>
#include <vimlop/Video/FrameSequence.h>
#include <vimlop/Video/TrackerTrajectory.h>
#include <vimlop/Video/VideoInput.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <zlib.h>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace vimlop;
using vimlop::fixtures::errorMessageOf;

namespace
{

/// What a test's recording holds; every field has the value PLUS writes.
struct Recording
{
  int width = 8;
  int height = 6;
  int channels = 3;
  std::string elementType = "MET_UCHAR";
  std::vector<std::string> status = { "OK", "OK", "OK" };
  std::vector<double> timestampsS = { 100.0, 100.04, 100.08 };
  bool compressed = false;
  /// Bytes dropped from the end of the pixel data.
  size_t truncatedBytes = 0;
};

/// Pixel (x, y) of frame f, channel c: a value the test can recompute.
unsigned char pixel(int f, int x, int y, int c)
{
  return static_cast<unsigned char>(40 * f + 7 * x + 3 * y + 50 * c);
}

std::string writeRecording(const std::string& path, const Recording& r)
{
  const int frames = static_cast<int>(r.status.size());
  std::string data;
  for (int f = 0; f < frames; ++f)
  {
    for (int y = 0; y < r.height; ++y)
    {
      for (int x = 0; x < r.width; ++x)
      {
        for (int c = 0; c < r.channels; ++c)
        {
          data.push_back(static_cast<char>(pixel(f, x, y, c)));
        }
      }
    }
  }
  if (r.compressed)
  {
    uLongf size = compressBound(static_cast<uLong>(data.size()));
    std::string packed(size, '\0');
    compress(reinterpret_cast<Bytef*>(packed.data()), &size,
      reinterpret_cast<const Bytef*>(data.data()), static_cast<uLong>(data.size()));
    packed.resize(size);
    data = packed;
  }
  data.resize(data.size() - r.truncatedBytes);
  std::ofstream out(path, std::ios::binary);
  out << "ObjectType = Image\nNDims = 3\nAnatomicalOrientation = RAI\nBinaryData = True\n"
      << "CompressedData = " << (r.compressed ? "True" : "False") << "\nDimSize = " << r.width
      << " " << r.height << " " << frames << "\nElementNumberOfChannels = " << r.channels
      << "\nElementType = " << r.elementType << "\nUltrasoundImageOrientation = MF\n";
  for (int f = 0; f < frames; ++f)
  {
    char prefix[32];
    std::snprintf(prefix, sizeof(prefix), "Seq_Frame%04d_", f);
    out << prefix << "ProbeToTrackerTransform = 1 0 0 " << 10.0 * f
        << " 0 1 0 20 0 0 1 30 0 0 0 1\n"
        << prefix << "ProbeToTrackerTransformStatus = OK\n";
    if (f < static_cast<int>(r.timestampsS.size()))
    {
      out << prefix << "Timestamp = " << r.timestampsS[f] << "\n";
    }
    out << prefix << "ImageStatus = " << r.status[f] << "\n";
  }
  out << "ElementDataFile = LOCAL\n" << data;
  return path;
}

} // namespace

TEST(TrackedSequence, LoadsTheFramesOfAPlusRecordingWithTheirTimestamps)
{
  const std::string dir = fixtures::freshTestFolder("tracked-sequence").string();
  for (const bool compressed : { false, true })
  {
    SCOPED_TRACE(compressed ? "compressed" : "raw");
    Recording r;
    r.compressed = compressed;
    r.status = { "OK", "INVALID", "OK" };
    const FrameSequence sequence =
      FrameSequence::load(writeRecording(dir + "/recording.igs.mha", r));
    ASSERT_EQ(sequence.size(), 2);
    EXPECT_EQ(sequence.ids(), (std::vector<int>{ 0, 2 }));
    EXPECT_EQ(sequence.timestampsS(), (std::vector<double>{ 100.0, 100.08 }));
    EXPECT_NEAR(sequence.framesPerSecond(), 25.0, 1e-9) << "frame 1, left out, counts";
    EXPECT_EQ(sequence.widthPx(), 8);
    EXPECT_EQ(sequence.heightPx(), 6);
    // RGB in the file, BGR in memory; rows as stored.
    const cv::Vec3b bgr = sequence.frame(1).at<cv::Vec3b>(4, 5);
    EXPECT_EQ(bgr[0], pixel(2, 5, 4, 2));
    EXPECT_EQ(bgr[1], pixel(2, 5, 4, 1));
    EXPECT_EQ(bgr[2], pixel(2, 5, 4, 0));
  }
  Recording grey;
  grey.channels = 1;
  const FrameSequence greyFrames = FrameSequence::load(writeRecording(dir + "/grey.seq.mha", grey));
  EXPECT_EQ(greyFrames.frame(2).at<cv::Vec3b>(1, 1), cv::Vec3b::all(pixel(2, 1, 1, 0)));
  EXPECT_EQ(FrameSequence::load(dir + "/grey.seq.mha", 2).size(), 2);
}

TEST(TrackedSequence, RefusesRecordingsItCannotReadWithTheReason)
{
  const std::string dir = fixtures::freshTestFolder("tracked-sequence-refusals").string();
  const auto loadError = [&](const std::string& name, const Recording& r)
  {
    const std::string path = writeRecording(dir + "/" + name, r);
    return errorMessageOf([&] { FrameSequence::load(path); });
  };
  Recording r;
  r.elementType = "MET_SHORT";
  EXPECT_EQ(loadError("short.igs.mha", r),
    "'" + dir +
      "/short.igs.mha': its pixels are MET_SHORT; a tracked video needs 8-bit pixels (MET_UCHAR)");
  r = Recording();
  r.timestampsS = { 100.0, 100.04 };
  EXPECT_EQ(loadError("untimed.igs.mha", r),
    "'" + dir + "/untimed.igs.mha': frame 2 has no Seq_Frame2_Timestamp");
  r = Recording();
  r.timestampsS = { 100.0, 100.04, 100.04 };
  EXPECT_EQ(loadError("still.igs.mha", r),
    "'" + dir +
      "/still.igs.mha': the timestamps do not increase: frame 2 is at 100.040000 s, the "
      "frame before it at 100.040000 s");
  r = Recording();
  r.truncatedBytes = 10;
  EXPECT_EQ(loadError("short-data.igs.mha", r),
    "'" + dir + "/short-data.igs.mha': its data ends inside frame 2 (422 of 432 bytes)");
  r = Recording();
  r.status = { "INVALID", "INVALID", "INVALID" };
  EXPECT_EQ(loadError("lost.igs.mha", r),
    "'" + dir + "/lost.igs.mha': holds no frame whose image status is OK");
  r = Recording();
  r.channels = 2;
  EXPECT_EQ(loadError("two.igs.mha", r),
    "'" + dir + "/two.igs.mha': frames of 2 channels are not read (1, 3 or 4)");
  std::ofstream(dir + "/flat.mha") << "ObjectType = Image\nNDims = 2\nDimSize = 4 4\n"
                                      "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n";
  EXPECT_EQ(errorMessageOf([&] { FrameSequence::load(dir + "/flat.mha"); }),
    "'" + dir + "/flat.mha': not a sequence of images (NDims must be 3: width, height and frames)");
  std::ofstream(dir + "/headless.mha") << "ObjectType = Image\nNDims = 3\n";
  EXPECT_EQ(errorMessageOf([&] { FrameSequence::load(dir + "/headless.mha"); }),
    "'" + dir + "/headless.mha': not a MetaImage (no ElementDataFile line ends its header)");
}

TEST(TrackedSequence, TheTrackerIsTheOriginOfTheNamedTransformAtEachTimestamp)
{
  const std::string dir = fixtures::freshTestFolder("tracked-sequence-tracker").string();
  const std::string path = writeRecording(dir + "/recording.igs.mha", Recording());
  const TrackerTrajectory tracker = TrackerTrajectory::readTrackedSequence(path, "ProbeToTracker");
  ASSERT_EQ(tracker.samples().size(), 3u);
  EXPECT_EQ(tracker.samples()[2].timeS, 100.08);
  EXPECT_EQ(tracker.samples()[2].positionMm, Eigen::Vector3d(20.0, 20.0, 30.0));
  EXPECT_EQ(
    errorMessageOf([&] { TrackerTrajectory::readTrackedSequence(path, "StylusToTracker"); }),
    "'" + path +
      "': holds no frame of the transform 'StylusToTracker' (no field "
      "Seq_Frame<n>_StylusToTrackerTransform with status OK)");
}

TEST(TrackedSequence, FrameTimesComeFromTheTimestampsUnlessAFrameRateOverridesThem)
{
  const std::vector<int> ids = { 0, 1, 2, 4 };
  const std::vector<double> stamps = { 100.0, 100.04, 100.08, 100.16 };
  std::string warning;
  EXPECT_EQ(frameTimesS(ids, stamps, 25.0, 0.0, 0.5, &warning),
    (std::vector<double>{ 100.5, 100.54, 100.58, 100.66 }));
  EXPECT_EQ(warning, "");

  const std::vector<double> overridden = frameTimesS(ids, stamps, 25.0, 30.0, 0.0, &warning);
  EXPECT_DOUBLE_EQ(overridden[0], 100.0) << "the rate is overridden, not the clock";
  EXPECT_DOUBLE_EQ(overridden[3], 100.0 + 4.0 / 30.0);
  EXPECT_EQ(warning,
    "the frame rate given, 30 fps, disagrees with the frames' own timestamps (25 fps); the "
    "frame times follow the rate given");
  warning.clear();
  frameTimesS(ids, stamps, 25.0, 25.1, 0.0, &warning);
  EXPECT_EQ(warning, "") << "within 1 %";

  // A video's own rate, then the user's against it, then none at all.
  EXPECT_DOUBLE_EQ(frameTimesS(ids, {}, 25.0, 0.0, 0.0, &warning)[3], 4.0 / 25.0);
  EXPECT_EQ(warning, "");
  frameTimesS(ids, {}, 25.0, 30.0, 0.0, &warning);
  EXPECT_EQ(warning,
    "the frame rate given, 30 fps, disagrees with the video's (25 fps); the frame times follow "
    "the rate given");
  const std::vector<double> assumed = frameTimesS(ids, {}, 0.0, 0.0, 0.0, &warning);
  EXPECT_DOUBLE_EQ(assumed[3], 4.0 / 30.0);
  EXPECT_EQ(warning,
    "the frames record no times: they are taken 30 fps apart (give the video's frame rate, e.g. "
    "--fps 25)");
  EXPECT_EQ(errorMessageOf([&] { frameTimesS(ids, stamps, 25.0, -1.0, 0.0, nullptr); }),
    "the frame rate must be positive (or 0: from the frames), got -1.000000");
}
