// Tracked image sequences as PLUS and 3D Slicer record them (.igs.mha,
// .igs.nrrd, .seq.nrrd): the frames with their timestamps, the tracker from
// one of their transforms, and the frames' times on the tracker's clock.

#include <vimlop/Core/Error.h>
#include <vimlop/Video/FrameSequence.h>
#include <vimlop/Video/FrameStream.h>
#include <vimlop/Video/TrackerTrajectory.h>
#include <vimlop/Video/VideoInput.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <opencv2/core.hpp>

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

/// The recording's pixels, compressed as zlib (MetaImage) or gzip (NRRD)
/// when asked, less `truncatedBytes`.
std::string pixelData(const Recording& r, bool gzip)
{
  std::string data;
  for (int f = 0; f < static_cast<int>(r.status.size()); ++f)
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
    z_stream stream{};
    deflateInit2(
      &stream, Z_DEFAULT_COMPRESSION, Z_DEFLATED, gzip ? 16 + 15 : 15, 8, Z_DEFAULT_STRATEGY);
    std::string packed(deflateBound(&stream, static_cast<uLong>(data.size())) + 32, '\0');
    stream.next_in = reinterpret_cast<Bytef*>(data.data());
    stream.avail_in = static_cast<uInt>(data.size());
    stream.next_out = reinterpret_cast<Bytef*>(packed.data());
    stream.avail_out = static_cast<uInt>(packed.size());
    deflate(&stream, Z_FINISH);
    packed.resize(stream.total_out);
    deflateEnd(&stream);
    data = packed;
  }
  data.resize(data.size() - r.truncatedBytes);
  return data;
}

/// Frame f's transform (translated 10 mm a frame along x) and status fields.
std::string frameFields(int f, const Recording& r, const std::string& separator)
{
  char prefix[32];
  std::snprintf(prefix, sizeof(prefix), "Seq_Frame%04d_", f);
  std::ostringstream out;
  out << prefix << "ProbeToTrackerTransform" << separator << "1 0 0 " << 10.0 * f
      << " 0 1 0 20 0 0 1 30 0 0 0 1\n"
      << prefix << "ProbeToTrackerTransformStatus" << separator << "OK\n";
  if (f < static_cast<int>(r.timestampsS.size()))
  {
    out << prefix << "Timestamp" << separator << r.timestampsS[f] << "\n";
  }
  out << prefix << "ImageStatus" << separator << r.status[f] << "\n";
  return out.str();
}

std::string writeRecording(const std::string& path, const Recording& r)
{
  const int frames = static_cast<int>(r.status.size());
  std::ofstream out(path, std::ios::binary);
  out << "ObjectType = Image\nNDims = 3\nAnatomicalOrientation = RAI\nBinaryData = True\n"
      << "CompressedData = " << (r.compressed ? "True" : "False") << "\nDimSize = " << r.width
      << " " << r.height << " " << frames << "\nElementNumberOfChannels = " << r.channels
      << "\nElementType = " << r.elementType << "\nUltrasoundImageOrientation = MF\n";
  for (int f = 0; f < frames; ++f)
  {
    out << frameFields(f, r, " = ");
  }
  out << "ElementDataFile = LOCAL\n" << pixelData(r, false);
  return path;
}

/// How a NRRD recording carries its frames' times.
enum class NrrdTimes
{
  /// PLUS's `.igs.nrrd`: `Seq_Frame<n>_Timestamp:=` keys.
  FrameFields,
  /// Slicer's `.seq.nrrd`: the sequence axis's index values, no frame keys.
  SequenceIndex
};

/// The recording as PLUS writes it in NRRD (gzip when compressed), or as
/// Slicer saves a volume sequence (MET_UCHAR written as NRRD's uchar).
std::string writeNrrdRecording(const std::string& path, const Recording& r, NrrdTimes times,
  const std::string& encoding = "", const std::string& unit = "s")
{
  const int frames = static_cast<int>(r.status.size());
  std::ofstream out(path, std::ios::binary);
  out << "NRRD0004\n# Complete NRRD file format specification at:\n"
      << "type: " << (r.elementType == "MET_UCHAR" ? "uchar" : r.elementType)
      << "\ndimension: " << (r.channels > 1 ? 5 : 4) << "\nspace: left-posterior-superior\nsizes: "
      << (r.channels > 1 ? std::to_string(r.channels) + " " : "") << r.width << " " << r.height
      << " 1 " << frames << "\nkinds: " << (r.channels > 1 ? "vector " : "")
      << "domain domain domain list\nencoding: "
      << (encoding.empty() ? (r.compressed ? "gzip" : "raw") : encoding) << "\n";
  if (times == NrrdTimes::FrameFields)
  {
    out << "UltrasoundImageOrientation:=MF\n";
    for (int f = 0; f < frames; ++f)
    {
      out << frameFields(f, r, ":=");
    }
  }
  else
  {
    out << "units: " << (r.channels > 1 ? "\"\" " : "") << "\"\" \"\" \"\" \"" << unit
        << "\"\naxis 3 index type:=numeric\naxis 3 index values:=";
    for (const double t : r.timestampsS)
    {
      out << t << " ";
    }
    out << "\n";
  }
  out << "\n" << pixelData(r, true);
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

TEST(TrackedSequence, StreamsItsFramesWithTheirTimestamps)
{
  // A tracker reading the frames one at a time needs each frame's time on
  // the tracker's clock, as the whole sequence has them.
  const std::string dir = fixtures::freshTestFolder("tracked-sequence-stream").string();
  Recording r;
  r.status = { "OK", "INVALID", "OK" };
  FrameStream stream = FrameStream::open(writeRecording(dir + "/recording.igs.mha", r));
  StreamedFrame f;
  std::vector<double> times;
  while (stream.next(f))
  {
    ASSERT_TRUE(f.timestampS.has_value()) << f.name;
    times.push_back(*f.timestampS);
  }
  EXPECT_EQ(times, (std::vector<double>{ 100.0, 100.08 }));
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

TEST(TrackedSequence, ReadsPlusAndSlicerNrrdRecordingsAsTheSameFrames)
{
  const std::string dir = fixtures::freshTestFolder("tracked-sequence-nrrd").string();
  for (const bool compressed : { false, true })
  {
    SCOPED_TRACE(compressed ? "gzip" : "raw");
    Recording r;
    r.compressed = compressed;
    r.status = { "OK", "INVALID", "OK" };
    const FrameSequence plus = FrameSequence::load(
      writeNrrdRecording(dir + "/recording.igs.nrrd", r, NrrdTimes::FrameFields));
    const FrameSequence metaImage =
      FrameSequence::load(writeRecording(dir + "/recording.igs.mha", r));
    ASSERT_EQ(plus.size(), 2);
    EXPECT_EQ(plus.ids(), metaImage.ids());
    EXPECT_EQ(plus.timestampsS(), metaImage.timestampsS());
    for (int f = 0; f < 2; ++f)
    {
      EXPECT_EQ(cv::norm(plus.frame(f), metaImage.frame(f), cv::NORM_INF), 0.0);
    }
  }
  Recording grey;
  grey.channels = 1;
  const FrameSequence slicer = FrameSequence::load(
    writeNrrdRecording(dir + "/video.seq.nrrd", grey, NrrdTimes::SequenceIndex));
  EXPECT_EQ(slicer.timestampsS(), grey.timestampsS) << "the sequence index, in seconds";
  EXPECT_NEAR(slicer.framesPerSecond(), 25.0, 1e-9);
  EXPECT_EQ(slicer.frame(2).at<cv::Vec3b>(5, 7), cv::Vec3b::all(pixel(2, 7, 5, 0)));

  // The transforms of a PLUS NRRD are read as those of its MetaImage.
  const TrackerTrajectory tracker = TrackerTrajectory::readTrackedSequence(
    writeNrrdRecording(dir + "/tracked.igs.nrrd", Recording(), NrrdTimes::FrameFields),
    "ProbeToTracker");
  ASSERT_EQ(tracker.samples().size(), 3u);
  EXPECT_EQ(tracker.samples()[1].timeS, 100.04);
  EXPECT_EQ(tracker.samples()[1].positionMm, Eigen::Vector3d(10.0, 20.0, 30.0));
}

TEST(TrackedSequence, RefusesNrrdRecordingsItCannotReadWithTheReason)
{
  const std::string dir = fixtures::freshTestFolder("tracked-sequence-nrrd-refusals").string();
  const auto loadError = [&](const std::string& name, const Recording& r, NrrdTimes times,
                           const std::string& encoding = "", const std::string& unit = "s")
  {
    const std::string path = writeNrrdRecording(dir + "/" + name, r, times, encoding, unit);
    return errorMessageOf([&] { FrameSequence::load(path); });
  };
  Recording r;
  r.elementType = "short";
  EXPECT_EQ(loadError("short.igs.nrrd", r, NrrdTimes::FrameFields),
    "'" + dir +
      "/short.igs.nrrd': its pixels are 'short'; a tracked video needs 8-bit pixels "
      "(uchar)");
  EXPECT_EQ(loadError("bzip.igs.nrrd", Recording(), NrrdTimes::FrameFields, "bzip2"),
    "'" + dir + "/bzip.igs.nrrd': its data are in 'bzip2' encoding; raw and gzip are read");
  EXPECT_EQ(loadError("frames.seq.nrrd", Recording(), NrrdTimes::SequenceIndex, "", "frame"),
    "'" + dir + "/frames.seq.nrrd': its sequence index is in 'frame', not in seconds (s)");
  r = Recording();
  r.timestampsS = { 100.0, 100.04 };
  EXPECT_EQ(loadError("untimed.seq.nrrd", r, NrrdTimes::SequenceIndex),
    "'" + dir +
      "/untimed.seq.nrrd': frame 2 has no Seq_Frame2_Timestamp and no sequence index "
      "value (axis 3 index values, in seconds)");
  r = Recording();
  r.compressed = true;
  r.truncatedBytes = 20;
  EXPECT_EQ(loadError("cut.igs.nrrd", r, NrrdTimes::FrameFields)
              .rfind("'" + dir + "/cut.igs.nrrd': its data ends inside frame ", 0),
    0u);
  std::ofstream(dir + "/volume.nrrd") << "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 8 6 "
                                         "5\nkinds: domain domain domain\nencoding: raw\n\n";
  EXPECT_EQ(errorMessageOf([&] { FrameSequence::load(dir + "/volume.nrrd"); }),
    "'" + dir + "/volume.nrrd': its last axis is of kind 'domain', not a list of frames");
  std::ofstream(dir + "/endless.nrrd") << "NRRD0004\ntype: uchar\nsizes: 8 6 5\n";
  EXPECT_EQ(errorMessageOf([&] { FrameSequence::load(dir + "/endless.nrrd"); }),
    "'" + dir + "/endless.nrrd': its NRRD header has no blank line before the data");
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

TEST(TrackedSequence, TheSensorsPoseIsInterpolatedBetweenSamplesAlongTheShorterArc)
{
  using Sample = TrackerTrajectory::Sample;
  const Eigen::Matrix3d quarterTurn =
    Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const TrackerTrajectory tracker(
    { Sample{ 10.0, Eigen::Vector3d(0, 0, 0), Eigen::Matrix3d::Identity() },
      Sample{ 11.0, Eigen::Vector3d(4, 0, 0), quarterTurn } });
  const std::optional<Eigen::Matrix4d> middle = tracker.poseAt(10.5);
  ASSERT_TRUE(middle.has_value());
  const Eigen::Matrix3d eighthTurn =
    Eigen::AngleAxisd(0.25 * M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_LT((middle->topLeftCorner<3, 3>() - eighthTurn).norm(), 1e-12);
  EXPECT_LT((middle->topRightCorner<3, 1>() - Eigen::Vector3d(2, 0, 0)).norm(), 1e-12);
  EXPECT_LT((tracker.poseAt(11.0)->topLeftCorner<3, 3>() - quarterTurn).norm(), 1e-12);
  EXPECT_FALSE(tracker.poseAt(11.5).has_value()) << "after the recording";
  const TrackerTrajectory positionsOnly(
    { Sample{ 10.0, Eigen::Vector3d(0, 0, 0) }, Sample{ 11.0, Eigen::Vector3d(4, 0, 0) } });
  EXPECT_FALSE(positionsOnly.poseAt(10.5).has_value()) << "a CSV tracker has no rotation";
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
