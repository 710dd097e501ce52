#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/DicomSeriesGeometry.h>

#include "DicomSliceWriter.h"
#include "ErrorMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>

using namespace vimlop;

namespace
{

/// An axial 8 x 8 slice of 0.5 mm pixels at height z (mm), named s<index>.
DicomSliceHeader axialSlice(int index, double z)
{
  DicomSliceHeader s;
  s.file = "s" + std::to_string(index);
  s.positionMm = { -2.0, 3.0, z };
  s.hasPosition = true;
  s.orientation = { 1, 0, 0, 0, 1, 0 };
  s.hasOrientation = true;
  s.pixelSpacingMm = { 0.5, 0.5 };
  s.hasPixelSpacing = true;
  s.rows = 8;
  s.columns = 8;
  s.pixelBytes = s.expectedPixelBytes = 8 * 8 * 2;
  return s;
}

std::vector<DicomSliceHeader> stackAt(const std::vector<double>& heights)
{
  std::vector<DicomSliceHeader> slices;
  for (std::size_t k = 0; k < heights.size(); ++k)
  {
    slices.push_back(axialSlice(static_cast<int>(k), heights[k]));
  }
  return slices;
}

std::string refusal(const std::vector<DicomSliceHeader>& slices)
{
  return fixtures::errorMessageOf([&] { checkDicomSeriesGeometry(slices); });
}

/// The 20-degree gantry tilt of the issue: slices tilted about the row
/// direction while their positions climb straight up z, 2 mm a slice.
void tilt(std::vector<DicomSliceHeader>& slices, double degrees)
{
  const double a = degrees * M_PI / 180.0;
  for (DicomSliceHeader& s : slices)
  {
    s.orientation = { 1, 0, 0, 0, std::cos(a), std::sin(a) };
  }
}

} // namespace

TEST(DicomSeriesGeometry, AnEvenStackIsOrderedAlongItsNormalWhateverTheFileOrder)
{
  const DicomSeriesLayout layout = checkDicomSeriesGeometry(stackAt({ 15, 10, 20, 12.5, 17.5 }));
  EXPECT_EQ(layout.order, (std::vector<std::size_t>{ 1, 3, 0, 4, 2 }));
  EXPECT_DOUBLE_EQ(layout.sliceStepMm, 2.5);
}

TEST(DicomSeriesGeometry, AGantryTiltIsRefusedWithItsAngle)
{
  std::vector<DicomSliceHeader> slices = stackAt({ 0, 2, 4, 6 });
  tilt(slices, 20.0);
  // Slice 1 lies 2 sin 20 = 0.68 mm beside the normal, 2 cos 20 = 1.88 mm up it.
  EXPECT_EQ(refusal(slices),
    "the slices are not stacked along their normal: 's1' lies 0.68 mm beside the normal through "
    "'s0', 1.88 mm from it (a gantry tilt or shear of 20.00 degrees); a regular volume of it "
    "would misplace the anatomy: resample it onto a regular grid (--resample-irregular-series)");
  // The same orientation with positions that follow the normal is a plain oblique stack.
  for (int k = 0; k < 4; ++k)
  {
    const double a = 20.0 * M_PI / 180.0;
    slices[k].positionMm = { 0.0, -2.0 * k * std::sin(a), 2.0 * k * std::cos(a) };
  }
  EXPECT_EQ(refusal(slices), "no error");
}

TEST(DicomSeriesGeometry, MissingSlicesAreRefusedNamingTheGapAndHowManyAreMissing)
{
  EXPECT_EQ(refusal(stackAt({ 0, 1, 2, 3, 9, 10, 11 })),
    "the slices are not evenly spaced: 's3' and 's4' are 6.00 mm apart where the series steps "
    "1.00 mm (5 slices are missing); a volume with one spacing would misplace the slices beyond "
    "them: resample it onto a regular grid (--resample-irregular-series)");
  EXPECT_EQ(refusal(stackAt({ 0, 1, 2, 3.5, 4.5, 5.5 })),
    "the slices are not evenly spaced: 's2' and 's3' are 1.50 mm apart where the series steps "
    "1.00 mm; a volume with one spacing would misplace the slices beyond them: resample it onto "
    "a regular grid (--resample-irregular-series)");
  // Rounding in the decimal strings (a hundredth of the step) is not a gap.
  EXPECT_EQ(refusal(stackAt({ 0, 1.004, 2, 2.997 })), "no error");
}

TEST(DicomSeriesGeometry, TwoSlicesAtOnePositionAreRefused)
{
  EXPECT_EQ(refusal(stackAt({ 0, 1, 1, 2 })),
    "slices 's1' and 's2' lie at the same position (1.00 mm along the slice normal); a series "
    "holds each slice once");
}

TEST(DicomSeriesGeometry, MixedOrientationsAreRefused)
{
  std::vector<DicomSliceHeader> slices = stackAt({ 0, 1, 2, 3 });
  const double a = 12.0 * M_PI / 180.0;
  slices[2].orientation = { std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0 };
  EXPECT_EQ(refusal(slices),
    "the slices do not share one orientation: 's2' is turned 12.00 degrees from 's0'; one volume "
    "needs one orientation");
}

TEST(DicomSeriesGeometry, OrientationVectorsThatAreNotOrthonormalAreRefused)
{
  std::vector<DicomSliceHeader> slices = stackAt({ 0, 1, 2 });
  slices[1].orientation = { 0, 0, 0, 0, 0, 0 };
  EXPECT_EQ(refusal(slices),
    "slice 's1': its Image Orientation (Patient) (0020,0037) is not two unit vectors at right "
    "angles (row length 0.000, column length 0.000, row . column 0.000)");
  slices[1].orientation = { 1, 0, 0, 0.6, 0.8, 0 };
  EXPECT_EQ(refusal(slices),
    "slice 's1': its Image Orientation (Patient) (0020,0037) is not two unit vectors at right "
    "angles (row length 1.000, column length 1.000, row . column 0.600)");
}

TEST(DicomSeriesGeometry, EachSliceNeedsAPositionASpacingAndAllItsPixels)
{
  std::vector<DicomSliceHeader> slices = stackAt({ 0, 1, 2 });
  slices[0].hasPosition = false;
  EXPECT_EQ(refusal(slices),
    "slice 's0': no Image Position (Patient) (0020,0032); without it the slice cannot be placed");
  slices = stackAt({ 0, 1, 2 });
  slices[2].positionMm[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(refusal(slices),
    "slice 's2': its Image Position (Patient) (0020,0032) is not three finite numbers");
  slices = stackAt({ 0, 1, 2 });
  slices[1].pixelSpacingMm[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(refusal(slices),
    "slice 's1': its Pixel Spacing (0028,0030) is not two finite positive numbers of at most "
    "100 mm");
  slices[1].hasPixelSpacing = false;
  EXPECT_EQ(refusal(slices), "slice 's1': no Pixel Spacing (0028,0030)");
  slices = stackAt({ 0, 1, 2 });
  slices[2].pixelBytes = 100;
  EXPECT_EQ(refusal(slices),
    "slice 's2': the file is truncated: it holds 100 bytes of pixel data where its header "
    "promises 128 (8 x 8 pixels)");
  slices = stackAt({ 0, 1, 2 });
  slices[1].columns = 9;
  EXPECT_EQ(refusal(slices), "the slices differ in size: 's1' is 8 x 9 pixels, 's0' 8 x 8");
  EXPECT_EQ(refusal(stackAt({ 4 })), "the DICOM series has a single slice; a 3-D CT is needed");
}

TEST(DicomSeriesGeometry, ATiltedStackWithAGapIsResampledWhereEachVoxelLiesWhenAsked)
{
  // 16 x 12 pixels of 0.75 mm along the rows and 0.5 mm between them, tilted
  // 20 degrees, climbing straight up z with 3 slices missing between 4 and 10.
  const double a = 20.0 * M_PI / 180.0;
  const std::vector<double> heights{ 0, 2, 4, 10, 12 };
  std::vector<DicomSliceHeader> slices = stackAt(heights);
  tilt(slices, 20.0);
  CTVolume stack;
  stack.dims = { 16, 12, static_cast<int>(heights.size()) };
  // A linear field of the patient frame: interpolation must give it back exactly.
  const auto field = [](const std::array<double, 3>& p)
  { return 0.3 * p[0] + 0.2 * p[1] + 0.5 * p[2]; };
  for (DicomSliceHeader& s : slices)
  {
    s.columns = 16;
    s.rows = 12;
    s.pixelSpacingMm = { 0.5, 0.75 };
    s.pixelBytes = s.expectedPixelBytes = 16 * 12 * 2;
    for (int j = 0; j < 12; ++j)
    {
      for (int i = 0; i < 16; ++i)
      {
        const std::array<double, 3> p{ s.positionMm[0] + 0.75 * i,
          s.positionMm[1] + 0.5 * j * std::cos(a), s.positionMm[2] + 0.5 * j * std::sin(a) };
        stack.intensities.push_back(static_cast<float>(field(p)));
      }
    }
  }
  const DicomSeriesLayout layout =
    checkDicomSeriesGeometry(slices, DicomSeriesTolerances(), IrregularSeries::Resample);
  ASSERT_EQ(layout.irregularities.size(), 2u);
  EXPECT_EQ(
    layout.irregularities[0].rfind("the slices are not stacked along their normal: ", 0), 0u);
  EXPECT_EQ(layout.irregularities[1],
    "the slices are not evenly spaced: 's2' and 's3' are 5.64 mm apart where the series steps "
    "1.88 mm (2 slices are missing)");

  const CTVolume volume = resampleDicomStack(stack, layout, slices[0]);
  EXPECT_EQ(volume.dims, (std::array<int, 3>{ 16, 12, 7 }));
  EXPECT_NEAR(volume.spacingMm[2], 2.0 * std::cos(a), 1e-9);
  int inside = 0;
  for (int m = 0; m < 7; ++m)
  {
    for (int j = 0; j < 12; ++j)
    {
      for (int i = 0; i < 16; ++i)
      {
        const float value = volume.intensities[static_cast<std::size_t>((m * 12 + j) * 16 + i)];
        if (value == -1024.0f)
        {
          // Only beside the shifted slices: the first slice is the grid's.
          EXPECT_GT(m, 0) << i << " " << j;
          continue;
        }
        ++inside;
        const double expected = field(volume.indexToPhysical({ double(i), double(j), double(m) }));
        ASSERT_NEAR(value, expected, 1e-3) << i << " " << j << " " << m;
      }
    }
  }
  EXPECT_GT(inside, 16 * 12 * 7 / 2);

  CTVolume wrong = stack;
  wrong.dims[2] = 4;
  EXPECT_EQ(fixtures::errorMessageOf([&] { resampleDicomStack(wrong, layout, slices[0]); }),
    "resampleDicomStack: the stack does not match the series layout");
}

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

/// The whole of a file, to change bytes of it.
std::string fileBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
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
  std::string bytes = fileBytes(file);
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
  std::string bytes = fileBytes(file);
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
  std::string bytes = fileBytes(file);
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
