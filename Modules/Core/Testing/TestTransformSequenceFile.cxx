#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/TransformSequenceFile.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace vimlop;
using vimlop::fixtures::errorMessageOf;

namespace
{

std::vector<TimedTransform> threeItemsAt25Fps()
{
  std::vector<TimedTransform> items;
  for (int i = 0; i < 3; ++i)
  {
    TimedTransform item;
    item.timeS = 12.0 + i / 25.0;
    item.matrix.topLeftCorner<3, 3>() =
      rotationFromVector(Eigen::Vector3d(0.1 * i, -0.7, 0.3 / 7.0));
    item.matrix.topRightCorner<3, 1>() = Eigen::Vector3d(-121.3 + i / 3.0, 100.25, 16.0 / 7.0);
    items.push_back(item);
  }
  return items;
}

std::string write(const std::string& folder, const std::string& name, const std::string& text)
{
  const std::string path = folder + "/" + name;
  std::ofstream(path) << text;
  return path;
}

} // namespace

TEST(TransformSequenceFile, WritesAndReadsBackEveryMatrixAndTimeExactly)
{
  const std::string dir = fixtures::freshTestFolder("sequence-round-trip").string();
  const std::vector<TimedTransform> items = threeItemsAt25Fps();
  writeTransformSequenceFile(items, "CameraToCT", dir + "/camera.seq.mha");
  const std::vector<TimedTransform> read =
    readTransformSequenceFile(dir + "/camera.seq.mha", "CameraToCT");
  ASSERT_EQ(read.size(), items.size());
  for (size_t i = 0; i < items.size(); ++i)
  {
    EXPECT_EQ(read[i].timeS, items[i].timeS);
    EXPECT_EQ(read[i].matrix, items[i].matrix);
  }
}

TEST(TransformSequenceFile, WritesTheFieldsSlicerReadsAsALinearTransformSequence)
{
  const std::string dir = fixtures::freshTestFolder("sequence-fields").string();
  writeTransformSequenceFile(threeItemsAt25Fps(), "CameraToCT", dir + "/camera.seq.mha");
  std::ifstream file(dir + "/camera.seq.mha");
  std::vector<std::string> lines;
  for (std::string line; std::getline(file, line);)
  {
    lines.push_back(line);
  }
  ASSERT_GE(lines.size(), 12u);
  EXPECT_EQ(lines.front(), "ObjectType = Image");
  EXPECT_EQ(lines.back(), "ElementDataFile = LOCAL");
  EXPECT_NE(std::find(lines.begin(), lines.end(), "DimSize = 0 0 3"), lines.end());
  EXPECT_NE(std::find(lines.begin(), lines.end(), "Seq_Frame0002_CameraToCTTransformStatus = OK"),
    lines.end());
  EXPECT_NE(std::find(lines.begin(), lines.end(), "Seq_Frame0001_Timestamp = 12.039999999999999"),
    lines.end());
}

TEST(TransformSequenceFile, ReadsAPlusRecordingAndSkipsFramesWhoseTransformIsMissing)
{
  // A PLUS-style tracked recording: two transforms, the probe lost in frame 1.
  const std::string dir = fixtures::freshTestFolder("sequence-plus").string();
  const std::string path = write(dir, "recording.igs.mha",
    "ObjectType = Image\nNDims = 3\nDimSize = 0 0 3\nElementType = MET_UCHAR\n"
    "Seq_Frame0000_ProbeToTrackerTransform = 1 0 0 10 0 1 0 20 0 0 1 30 0 0 0 1\n"
    "Seq_Frame0000_ProbeToTrackerTransformStatus = OK\n"
    "Seq_Frame0000_ReferenceToTrackerTransform = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
    "Seq_Frame0000_Timestamp = 100.5\n"
    "Seq_Frame0001_ProbeToTrackerTransform = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
    "Seq_Frame0001_ProbeToTrackerTransformStatus = MISSING\n"
    "Seq_Frame0001_Timestamp = 100.54\n"
    "Seq_Frame0002_ProbeToTrackerTransform = 1 0 0 11 0 1 0 20 0 0 1 30 0 0 0 1\n"
    "Seq_Frame0002_ProbeToTrackerTransformStatus = OK\n"
    "Seq_Frame0002_Timestamp = 100.58\n"
    "ElementDataFile = LOCAL\n");
  const std::vector<TimedTransform> items = readTransformSequenceFile(path, "ProbeToTracker");
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[0].timeS, 100.5);
  EXPECT_EQ(items[1].timeS, 100.58);
  EXPECT_EQ(items[1].matrix(0, 3), 11.0);
}

TEST(TransformSequenceFile, RefusesWhatItCannotWriteWithTheReason)
{
  const std::string dir = fixtures::freshTestFolder("sequence-refusals").string();
  const std::string path = dir + "/camera.seq.mha";
  EXPECT_EQ(errorMessageOf([&] { writeTransformSequenceFile({}, "CameraToCT", path); }),
    "'" + path + "': the transform sequence to write is empty");
  EXPECT_EQ(
    errorMessageOf([&] { writeTransformSequenceFile(threeItemsAt25Fps(), "Camera To CT", path); }),
    "'" + path + "': the transform name 'Camera To CT' is not letters and digits");
  std::vector<TimedTransform> items = threeItemsAt25Fps();
  items[2].timeS = items[1].timeS + 0.0004;
  EXPECT_EQ(errorMessageOf([&] { writeTransformSequenceFile(items, "CameraToCT", path); }),
    "'" + path +
      "': the times of items 1 and 2 (12.039999999999999 s, 12.0404 s) do not increase "
      "by at least 1 ms");
  items = threeItemsAt25Fps();
  items[1].matrix(2, 3) = std::nan("");
  EXPECT_EQ(errorMessageOf([&] { writeTransformSequenceFile(items, "CameraToCT", path); }),
    "'" + path + "': item 1 of the sequence has a value that is not finite");
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(TransformSequenceFile, RefusesFilesThatAreNotASequenceOfTheTransform)
{
  const std::string dir = fixtures::freshTestFolder("sequence-bad-files").string();
  EXPECT_EQ(
    errorMessageOf([&] { readTransformSequenceFile(dir + "/absent.seq.mha", "CameraToCT"); }),
    "'" + dir + "/absent.seq.mha': no such file, or it cannot be read");

  const std::string noHeader = write(dir, "no-header.seq.mha", "Seq_Frame0000_Timestamp = 1\n");
  EXPECT_EQ(errorMessageOf([&] { readTransformSequenceFile(noHeader, "CameraToCT"); }),
    "'" + noHeader + "': not a sequence metafile (no ObjectType line)");

  const std::string other = write(dir, "other.seq.mha",
    "ObjectType = Image\nSeq_Frame0000_ProbeToTrackerTransform = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
    "Seq_Frame0000_Timestamp = 1\nElementDataFile = LOCAL\n");
  EXPECT_EQ(errorMessageOf([&] { readTransformSequenceFile(other, "CameraToCT"); }),
    "'" + other +
      "': holds no frame of the transform 'CameraToCT' (no field "
      "Seq_Frame<n>_CameraToCTTransform with status OK)");

  const std::string shortMatrix = write(dir, "short.seq.mha",
    "ObjectType = Image\nSeq_Frame0000_CameraToCTTransform = 1 0 0 0 0 1 0 0 0 0 1 0\n");
  EXPECT_EQ(errorMessageOf([&] { readTransformSequenceFile(shortMatrix, "CameraToCT"); }),
    "'" + shortMatrix + "': frame 0's CameraToCTTransform is not 16 numbers");

  const std::string untimed = write(dir, "untimed.seq.mha",
    "ObjectType = Image\nSeq_Frame0000_CameraToCTTransform = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n");
  EXPECT_EQ(errorMessageOf([&] { readTransformSequenceFile(untimed, "CameraToCT"); }),
    "'" + untimed + "': frame 0 has a CameraToCTTransform but no timestamp");

  const std::string badTime = write(dir, "bad-time.seq.mha",
    "ObjectType = Image\nSeq_Frame0000_CameraToCTTransform = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
    "Seq_Frame0000_Timestamp = soon\n");
  EXPECT_EQ(errorMessageOf([&] { readTransformSequenceFile(badTime, "CameraToCT"); }),
    "'" + badTime + "': frame 0's timestamp 'soon' is not a number");
}
