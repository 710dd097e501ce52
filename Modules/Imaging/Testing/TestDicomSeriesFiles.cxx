#include <vimlop/Imaging/CTVolumeIO.h>

#include "DicomSliceWriter.h"
#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <utility>

using namespace vimlop;

// The same checks on files, through readCTVolume(): a regular series reads
// back as written, and each flaw is refused with the folder's name first.

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;

std::string writeSeries(const std::string& name, std::vector<fixtures::DicomSliceSpec> slices)
{
  const std::string folder = out + "/dicom-" + name;
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  fixtures::writeDicomSeries(folder, slices);
  return folder;
}

std::vector<fixtures::DicomSliceSpec> axialSeries(int count, double stepMm)
{
  std::vector<fixtures::DicomSliceSpec> slices(count);
  for (int k = 0; k < count; ++k)
  {
    slices[k].instance = k + 1;
    slices[k].position = "-2\\3\\" + std::to_string(5.0 + stepMm * k);
    slices[k].value = static_cast<std::int16_t>(100 * k - 1000);
  }
  return slices;
}

std::string readError(const std::string& folder)
{
  return fixtures::errorMessageOf([&] { readCTVolume(folder); });
}

} // namespace

TEST(DicomSeriesFiles, ARegularSeriesReadsBackAsWritten)
{
  std::vector<fixtures::DicomSliceSpec> slices = axialSeries(4, 2.5);
  std::swap(slices[0], slices[3]); // file order is not slice order
  const CTVolume volume = readCTVolume(writeSeries("regular", slices));
  EXPECT_EQ(volume.dims, (std::array<int, 3>{ 8, 8, 4 }));
  EXPECT_NEAR(volume.spacingMm[2], 2.5, 1e-6);
  EXPECT_NEAR(volume.originMm[2], 5.0, 1e-6);
  // Who and what the scan is, for the result folder.
  EXPECT_EQ(volume.identity,
    (std::map<std::string, std::string>{ { "patient_id", "PHANTOM" },
      { "series_instance_uid", "1.2.826.0.1.3680043.2.1125.2001" },
      { "study_instance_uid", "1.2.826.0.1.3680043.2.1125.2001.0" } }));
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_EQ(volume.intensities[static_cast<std::size_t>(k) * 64 + 9], 100.0f * k - 1000.0f);
  }
}

TEST(DicomSeriesFiles, ATiltedSeriesAGapAndATruncatedSliceAreRefusedBeforeAVolumeIsMade)
{
  std::vector<fixtures::DicomSliceSpec> tilted = axialSeries(4, 2.0);
  for (auto& s : tilted)
  {
    s.orientation = "1\\0\\0\\0\\0.93969262\\0.34202014"; // 20 degrees
  }
  const std::string tiltedFolder = writeSeries("tilted", tilted);
  EXPECT_EQ(readError(tiltedFolder),
    "'" + tiltedFolder + "': the slices are not stacked along their normal: '" + tiltedFolder +
      "/slice1.dcm' lies 0.68 mm beside the normal through '" + tiltedFolder +
      "/slice0.dcm', 1.88 mm from it (a gantry tilt or shear of 20.00 degrees); a regular "
      "volume of it would misplace the anatomy: resample it onto a regular grid "
      "(--resample-irregular-series)");

  std::vector<fixtures::DicomSliceSpec> gap = axialSeries(8, 1.0);
  gap.erase(gap.begin() + 3, gap.begin() + 5);
  const std::string gapFolder = writeSeries("gap", gap);
  EXPECT_EQ(readError(gapFolder),
    "'" + gapFolder + "': the slices are not evenly spaced: '" + gapFolder + "/slice2.dcm' and '" +
      gapFolder +
      "/slice3.dcm' are 3.00 mm apart where the series steps 1.00 mm (2 slices are missing); a "
      "volume with one spacing would misplace the slices beyond them: resample it onto a "
      "regular grid (--resample-irregular-series)");

  std::vector<fixtures::DicomSliceSpec> nanSpacing = axialSeries(3, 1.0);
  nanSpacing[1].pixelSpacing = "nan\\0.5";
  const std::string nanFolder = writeSeries("nan-spacing", nanSpacing);
  EXPECT_EQ(readError(nanFolder),
    "'" + nanFolder + "': slice '" + nanFolder +
      "/slice1.dcm': its Pixel Spacing (0028,0030) is not two finite positive numbers of at "
      "most 100 mm");

  std::vector<fixtures::DicomSliceSpec> truncated = axialSeries(3, 1.0);
  truncated[2].truncateBytes = 28;
  const std::string truncatedFolder = writeSeries("truncated", truncated);
  // Refused while the folder's files are walked, before GDCM allocates what they declare.
  EXPECT_EQ(readError(truncatedFolder),
    "'" + truncatedFolder +
      "/slice2.dcm': the file is truncated: element (7FE0,0010) at byte 624 declares 128 bytes "
      "and 100 are left");
}

TEST(DicomSeriesFiles, AGapIsBridgedAndSaidWhenResamplingIsAsked)
{
  std::vector<fixtures::DicomSliceSpec> gap = axialSeries(8, 1.0);
  gap.erase(gap.begin() + 3, gap.begin() + 5);
  const std::string folder = writeSeries("gap-resampled", gap);
  CTReadOptions options;
  options.resampleIrregularSeries = true;
  const CTVolume volume = readCTVolume(folder, options);
  EXPECT_EQ(volume.dims, (std::array<int, 3>{ 8, 8, 8 }));
  EXPECT_NEAR(volume.spacingMm[2], 1.0, 1e-6);
  EXPECT_NEAR(volume.originMm[2], 5.0, 1e-6);
  // The written slices keep their values, the missing ones lie on the line between.
  for (int k = 0; k < 8; ++k)
  {
    EXPECT_NEAR(
      volume.intensities[static_cast<std::size_t>(k) * 64 + 9], 100.0f * k - 1000.0f, 1e-3)
      << k;
  }
  const std::string said = "resampled onto a regular grid of 8 slices 1.00 mm apart along the "
                           "normal of '" +
    folder +
    "/slice0.dcm', as asked, from an irregular series: the slices are not evenly spaced: '" +
    folder + "/slice2.dcm' and '" + folder +
    "/slice3.dcm' are 3.00 mm apart where the series steps 1.00 mm (2 slices are missing). "
    "Voxels beside the slices' pixels are -1024 HU (air)";
  ASSERT_EQ(volume.warnings.size(), 1u);
  EXPECT_EQ(volume.warnings[0], said);
  EXPECT_EQ(volume.identity.at("resampled"), said);
  // Without the option the same folder is refused (above).
  EXPECT_NE(readError(folder).find("(--resample-irregular-series)"), std::string::npos);
}

TEST(DicomSeriesFiles, ACorruptFileMetaGroupIsRefusedBeforeGDCMParsesIt)
{
  // GDCM, built with assertions, aborted the process on an invalid VR there.
  std::vector<fixtures::DicomSliceSpec> slices = axialSeries(3, 1.0);
  const std::string folder = writeSeries("bad-meta", slices);
  const std::string file = folder + "/slice1.dcm";
  std::string bytes = fixtures::fileBytes(file);
  const std::string transferSyntax("\x02\x00\x10\x00UI", 6);
  ASSERT_NE(bytes.find(transferSyntax), std::string::npos);
  bytes[bytes.find(transferSyntax) + 4] = '?';
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_EQ(readError(folder),
    "'" + file +
      "': the DICOM file is corrupt: element (0002,0010) at byte 234 has the value "
      "representation '?I' where the standard has UI");
  EXPECT_EQ(readError(file),
    "'" + file +
      "': the DICOM file is corrupt: element (0002,0010) at byte 234 has the value "
      "representation '?I' where the standard has UI");
  const std::string notDicom = out + "/not-part-10.dcm";
  std::ofstream(notDicom, std::ios::binary) << std::string(200, '\0');
  EXPECT_EQ(readError(notDicom), "'" + notDicom + "': not a DICOM file (no 'DICM' at byte 128)");
}

TEST(DicomSeriesFiles, FilesWithoutThePreambleAreNeverHandedToGDCM)
{
  // Ten bytes GDCM took for big-endian DICOM and aborted on (an assertion).
  const std::string folder = writeSeries("stray-file", axialSeries(3, 1.0));
  std::ofstream(folder + "/stray.dcm", std::ios::binary)
    << std::string("\xff\xfc\xff\xfe\x00UN\x01\x00\x02", 10);
  std::ofstream(folder + "/README.txt") << "scanned on the phantom";
  const CTVolume volume = readCTVolume(folder);
  EXPECT_EQ(volume.dims, (std::array<int, 3>{ 8, 8, 3 }));
  EXPECT_TRUE(volume.warnings.empty());
}

TEST(DicomSeriesFiles, BytesTooFewForAnElementAtTheEndAreATruncation)
{
  // GDCM read them as a tag and a value representation and aborted.
  const std::string folder = writeSeries("tail-bytes", axialSeries(3, 1.0));
  const std::string file = folder + "/slice0.dcm";
  const auto size = std::filesystem::file_size(file);
  std::ofstream(file, std::ios::binary | std::ios::app)
    << std::string("\x28\xfe\x70\xfe\x70\xfe", 6);
  EXPECT_EQ(readError(folder),
    "'" + file + "': the file is truncated: it ends inside an element at byte " +
      std::to_string(size));
}

TEST(DicomSeriesFiles, AMetaElementBeyondTheGroupLengthIsRefused)
{
  // GDCM asserted when a meta element ran past the group's declared length.
  const std::string folder = writeSeries("group-length", axialSeries(3, 1.0));
  const std::string file = folder + "/slice2.dcm";
  std::string bytes = fixtures::fileBytes(file);
  ASSERT_EQ(bytes.compare(132, 6, std::string("\x02\x00\x00\x00UL", 6)), 0);
  bytes[140] = static_cast<char>(bytes[140] - 4); // the group length, 4 bytes short
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  const std::string message = readError(folder);
  EXPECT_EQ(message.rfind("'" + file + "': the DICOM file is corrupt: element (0002,", 0), 0u)
    << message;
}

TEST(DicomSeriesFiles, AFileWithoutItsMetaGroupIsRefused)
{
  std::string onlyLength(128, '\0');
  onlyLength += "DICM";
  onlyLength += std::string("\x02\x00\x00\x00UL\x04\x00\xe4\x00\x00\x00", 12);
  const std::string cut = out + "/meta-cut.dcm";
  std::ofstream(cut, std::ios::binary) << onlyLength;
  EXPECT_EQ(readError(cut),
    "'" + cut + "': the file is truncated: its file meta group declares 228 bytes and 0 are left");
  std::string bytes(128, '\0');
  bytes += "DICM";
  bytes += std::string("\x08\x00\x60\x00"
                       "CS\x02\x00"
                       "CT",
    10);
  const std::string path = out + "/no-meta.dcm";
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_EQ(readError(path),
    "'" + path + "': the DICOM file has no file meta information group (0002) after 'DICM'");
}

TEST(DicomSeriesFiles, AnImageAttributeOfTheWrongLengthIsRefused)
{
  // GDCM asserted on Rows (0028,0010) of 4 bytes: it reads one 16-bit number.
  const std::string folder = writeSeries("rows-length", axialSeries(3, 1.0));
  const std::string file = folder + "/slice1.dcm";
  std::string bytes = fixtures::fileBytes(file);
  const std::string rows("\x28\x00\x10\x00US\x02\x00", 8);
  const std::size_t at = bytes.find(rows);
  ASSERT_NE(at, std::string::npos);
  bytes[at + 6] = 4;
  bytes.insert(at + 10, 2, '\0');
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_EQ(readError(folder),
    "'" + file + "': the DICOM file is corrupt: element (0028,0010) at byte " + std::to_string(at) +
      " holds 4 bytes where one 16-bit number belongs");
}

namespace
{

/// In `file`, the value of the 2-byte attribute (0028,element), of VR `vr`,
/// replaced by `value` (2 bytes); returns where the element starts.
std::size_t setShortAttribute(
  const std::string& file, std::uint16_t element, const char* vr, const std::string& value)
{
  std::string bytes = fixtures::fileBytes(file);
  const std::string tag = std::string("\x28\x00", 2) + static_cast<char>(element & 0xff) +
    static_cast<char>(element >> 8) + vr + std::string("\x02\x00", 2);
  const std::size_t at = bytes.find(tag);
  EXPECT_NE(at, std::string::npos);
  if (at != std::string::npos)
  {
    bytes.replace(at + 8, 2, value);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  }
  return at;
}

/// Slice 1 of a fresh series with image attribute (0028,element), of VR US,
/// set to `value`; returns the file and where the element starts.
std::pair<std::string, std::size_t> withImageAttribute(
  const std::string& name, std::uint16_t element, std::uint16_t value)
{
  const std::string file = writeSeries(name, axialSeries(3, 1.0)) + "/slice1.dcm";
  const char bytes[2] = { static_cast<char>(value & 0xff), static_cast<char>(value >> 8) };
  return { file, setShortAttribute(file, element, "US", std::string(bytes, 2)) };
}

} // namespace

TEST(DicomSeriesFiles, PixelFormatValuesGDCMAssertsOnAreRefusedNamingTheAttribute)
{
  // GDCM (built with assertions) aborted the process on a Samples per Pixel of 2.
  const struct
  {
    std::uint16_t element;
    std::uint16_t value;
    const char* problem;
  } cases[] = {
    { 0x0002, 2, "gives Samples per Pixel 2, where DICOM allows 1, 3 or 4" },
    { 0x0002, 0, "gives Samples per Pixel 0, where DICOM allows 1, 3 or 4" },
    { 0x0100, 12, "gives Bits Allocated 12; VIMLOP reads 8, 16 or 32" },
    { 0x0101, 17, "gives Bits Stored 17, not from 1 to the Bits Allocated of 16" },
    { 0x0101, 0, "gives Bits Stored 0, not from 1 to the Bits Allocated of 16" },
    { 0x0102, 16, "gives High Bit 16, not below the Bits Stored of 16" },
    { 0x0103, 2, "gives Pixel Representation 2, where DICOM allows 0 (unsigned) or 1 (signed)" },
  };
  for (const auto& c : cases)
  {
    const auto [file, at] = withImageAttribute("pixel-format", c.element, c.value);
    char tag[16];
    std::snprintf(tag, sizeof(tag), "(0028,%04X)", c.element);
    EXPECT_EQ(readError(file),
      "'" + file + "': the DICOM file is corrupt: element " + tag + " at byte " +
        std::to_string(at) + " " + c.problem);
  }
  // Values within those bounds are read: 12 of 16 bits stored, high bit 11.
  withImageAttribute("pixel-format-12", 0x0101, 12);
  const std::string folder = out + "/dicom-pixel-format-12";
  const std::string file = folder + "/slice1.dcm";
  std::string bytes = fixtures::fileBytes(file);
  const std::size_t highBit = bytes.find(std::string("\x28\x00\x02\x01US\x02\x00", 8));
  ASSERT_NE(highBit, std::string::npos);
  bytes[highBit + 8] = 11;
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_EQ(readCTVolume(folder).dims, (std::array<int, 3>{ 8, 8, 3 }));
}

TEST(DicomSeriesFiles, ABigEndianFileIsRefusedByItsTransferSyntax)
{
  const std::string folder = writeSeries("big-endian", axialSeries(3, 1.0));
  const std::string file = folder + "/slice0.dcm";
  std::string bytes = fixtures::fileBytes(file);
  const std::string littleEndian("1.2.840.10008.1.2.1\0", 20);
  const std::size_t at = bytes.find(littleEndian);
  ASSERT_NE(at, std::string::npos);
  bytes[at + 18] = '2';
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_EQ(readError(folder),
    "'" + file +
      "': the DICOM file's transfer syntax 1.2.840.10008.1.2.2 (explicit VR big endian, retired) "
      "is not read; convert the series to explicit VR little endian");
}

TEST(DicomSeriesFiles, AnAttributeGDCMReadsAsATypedValueMustHaveItsStandardVR)
{
  // GDCM asserted on a Rescale Slope (0028,1053) written as US, not DS.
  const std::string folder = writeSeries("slope-vr", axialSeries(3, 1.0));
  const std::string file = folder + "/slice2.dcm";
  std::string bytes = fixtures::fileBytes(file);
  const std::size_t at = bytes.find(std::string("\x28\x00\x53\x10"
                                                "DS",
    6));
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at + 4, 2, "US");
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_EQ(readError(folder),
    "'" + file + "': the DICOM file is corrupt: element (0028,1053) at byte " + std::to_string(at) +
      " has the value representation 'US' where the standard has DS");
}

namespace
{

/// Slice 0 of a fresh series with `bytes` appended to its data set (after
/// the pixel data, where any element may stand for the walk); returns the
/// file and where they start.
std::pair<std::string, std::size_t> withTrailingElements(
  const std::string& name, const std::string& bytes)
{
  const std::string file = writeSeries(name, axialSeries(3, 1.0)) + "/slice0.dcm";
  const std::size_t at = std::filesystem::file_size(file);
  std::ofstream(file, std::ios::binary | std::ios::app) << bytes;
  return { file, at };
}

} // namespace

TEST(DicomSeriesFiles, AnItemOutsideAnySequenceIsRefused)
{
  // GDCM took the file for another encoding and allocated 4 GB for it.
  const auto [file, at] =
    withTrailingElements("stray-item", std::string("\xfe\xff\x00\xe0\x00\x00\x00\x00", 8));
  EXPECT_EQ(readError(file),
    "'" + file + "': the DICOM file is corrupt: element (FFFE,E000) at byte " + std::to_string(at) +
      " is an item or delimiter outside any sequence");
}

TEST(DicomSeriesFiles, TheElementsOfAnItemOfDefinedLengthAreWalkedToo)
{
  // (0040,9096) Real World Value Mapping Sequence, 26 bytes: one item of 18
  // bytes holding a Rescale Slope (0028,1053) written as US.
  std::string sequence("\x40\x00\x96\x90SQ\x00\x00\x1a\x00\x00\x00", 12);
  sequence += std::string("\xfe\xff\x00\xe0\x12\x00\x00\x00", 8);
  sequence += std::string("\x28\x00\x53\x10US\x02\x00\x01\x00", 10);
  // The item's last 8 bytes: an empty Manufacturer (0008,0070).
  sequence += std::string("\x08\x00\x70\x00LO\x00\x00", 8);
  const auto [file, at] = withTrailingElements("item-vr", sequence);
  EXPECT_EQ(readError(file),
    "'" + file + "': the DICOM file is corrupt: element (0028,1053) at byte " +
      std::to_string(at + 20) + " has the value representation 'US' where the standard has DS");
}

TEST(DicomSeriesFiles, AFileThatEndsWithItsMetaGroupIsATruncation)
{
  const std::string folder = writeSeries("meta-only", axialSeries(3, 1.0));
  const std::string file = folder + "/slice1.dcm";
  std::string bytes = fixtures::fileBytes(file);
  const std::size_t groupEnd = 144 + static_cast<unsigned char>(bytes[140]);
  ASSERT_EQ(bytes[141], '\0');
  bytes.resize(groupEnd);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_EQ(readError(folder),
    "'" + file + "': the file is truncated: it ends after its file meta group, without a data set");
}

TEST(DicomSeriesFiles, ARecognitionCodeOtherThanACRNEMAsIsRefused)
{
  // GDCM asserted that a file with the retired (0008,0010) was ACR-NEMA.
  const std::string folder = writeSeries("recognition-code", axialSeries(3, 1.0));
  const std::string file = folder + "/slice0.dcm";
  std::string bytes = fixtures::fileBytes(file);
  const std::size_t at = bytes.find(std::string("\x08\x00\x16\x00UI", 6)); // SOP Class UID
  ASSERT_NE(at, std::string::npos);
  bytes.insert(at, std::string("\x08\x00\x10\x00SH\x04\x00JUNK", 12));
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_EQ(readError(folder),
    "'" + file + "': the DICOM file is corrupt: element (0008,0010) at byte " + std::to_string(at) +
      " gives the retired Recognition Code 'JUNK'; GDCM reads only ACR-NEMA 1.0 or 2.0 there");
  bytes.replace(at + 6, 6, std::string("\x0c\x00", 2) + "ACR-NEMA 2.0");
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_EQ(readCTVolume(folder).dims, (std::array<int, 3>{ 8, 8, 3 }));
}

TEST(DicomSeriesFiles, ARescaleThatNarrowsThePixelTypeIsRefusedBeforeITKAbortsOnIt)
{
  // ITK's DICOM reader asserted "Pixel type larger than output type".
  const std::string zero = withImageAttribute("rescale-zero", 0x0100, 16).first;
  setShortAttribute(zero, 0x1053, "DS", "0 ");
  EXPECT_EQ(readError(zero),
    "'" + zero +
      "': the DICOM file is corrupt: the Rescale Slope 0 and Intercept 0 of its 16 signed bits "
      "stored (of 16) map the pixels onto a narrower type, on which ITK's DICOM reader aborts");
  const std::string six = withImageAttribute("rescale-six-bits", 0x0101, 6).first;
  setShortAttribute(six, 0x0102, "US", std::string("\x05\x00", 2));
  setShortAttribute(six, 0x0103, "US", std::string("\x00\x00", 2));
  setShortAttribute(six, 0x1053, "DS", "2 ");
  EXPECT_EQ(readError(six),
    "'" + six +
      "': the DICOM file is corrupt: the Rescale Slope 2 and Intercept 0 of its 6 unsigned bits "
      "stored (of 16) map the pixels onto a narrower type, on which ITK's DICOM reader aborts");
  const std::string text = withImageAttribute("rescale-text", 0x0100, 16).first;
  setShortAttribute(text, 0x1053, "DS", "x ");
  const std::string message = readError(text);
  EXPECT_NE(message.find("gives the Rescale Slope 'x', not a number"), std::string::npos)
    << message;
  // A rescale that keeps the type: 12 of 16 bits stored, unsigned, doubled.
  const std::string folder = writeSeries("rescale-ct", axialSeries(3, 1.0));
  for (int k = 0; k < 3; ++k)
  {
    const std::string slice = folder + "/slice" + std::to_string(k) + ".dcm";
    setShortAttribute(slice, 0x0101, "US", std::string("\x0c\x00", 2));
    setShortAttribute(slice, 0x0102, "US", std::string("\x0b\x00", 2));
    setShortAttribute(slice, 0x0103, "US", std::string("\x00\x00", 2));
    setShortAttribute(slice, 0x1053, "DS", "2 ");
  }
  EXPECT_EQ(readCTVolume(folder).dims, (std::array<int, 3>{ 8, 8, 3 }));
}
