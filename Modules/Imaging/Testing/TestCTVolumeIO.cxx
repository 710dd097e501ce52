#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Imaging/CTVolumeIO.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <limits>
#include <tuple>

using namespace vimlop;

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;

CTVolume makeVolume()
{
  CTVolume v;
  v.dims = { 7, 5, 4 };
  v.spacingMm = { 0.8, 0.9, 1.7 };
  v.originMm = { -12.5, 40.0, 3.25 };
  // An oblique acquisition: rotated axes.
  const Eigen::Matrix3d r = rotationFromVector(Eigen::Vector3d(0.1, -0.2, 0.3));
  for (int i = 0; i < 9; ++i)
  {
    v.direction[i] = r(i / 3, i % 3);
  }
  v.intensities.resize(v.numberOfVoxels());
  for (size_t i = 0; i < v.intensities.size(); ++i)
  {
    v.intensities[i] = static_cast<float>(static_cast<int>(i) * 7 - 1000);
  }
  return v;
}

std::string messageOf(const std::string& path)
{
  try
  {
    readCTVolume(path);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

class CTVolumeRoundTrip : public ::testing::TestWithParam<std::string>
{
};

TEST_P(CTVolumeRoundTrip, KeepsGeometryAndIntensities)
{
  const CTVolume v = makeVolume();
  // One base name per format: ctest runs the formats in parallel, and the
  // NIfTI reader given "roundtrip.nii.gz" also looks for "roundtrip.nii".
  std::string stem = GetParam();
  std::replace(stem.begin(), stem.end(), '.', '-');
  const std::string path = out + "/roundtrip" + stem + GetParam();
  writeCTVolume(v, path);
  const CTVolume back = readCTVolume(path);
  EXPECT_EQ(back.dims, v.dims);
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_NEAR(back.spacingMm[i], v.spacingMm[i], 1e-5);
    EXPECT_NEAR(back.originMm[i], v.originMm[i], 1e-4);
  }
  for (int i = 0; i < 9; ++i)
  {
    EXPECT_NEAR(back.direction[i], v.direction[i], 1e-5);
  }
  ASSERT_EQ(back.intensities.size(), v.intensities.size());
  for (size_t i = 0; i < v.intensities.size(); ++i)
  {
    ASSERT_EQ(back.intensities[i], v.intensities[i]);
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, CTVolumeRoundTrip,
  ::testing::Values(".nii.gz", ".nii", ".nrrd", ".mha", ".mhd"),
  [](const auto& info)
  {
    std::string name = info.param.substr(1);
    std::replace(name.begin(), name.end(), '.', '_');
    return name;
  });

TEST(CTVolumeIO, ReadsADicomSeriesSortedByPosition)
{
  // Fixture: two series in one folder (Testing/Data/DicomTwoSeries/README.md):
  // 1.2.826.0.1.3680043.2.1125.1001 with 6 slices of 10x12 whose file names
  // are shuffled, and ...1002 with 3 slices.
  const std::string folder = std::string(VIMLOP_TEST_DATA_DIR) + "/DicomTwoSeries";
  const CTVolume largest = readCTVolume(folder);
  EXPECT_EQ(largest.format, "DICOM series");
  EXPECT_EQ(largest.dims, (std::array<int, 3>{ 10, 12, 6 }));
  ASSERT_EQ(largest.warnings.size(), 1u);
  EXPECT_NE(largest.warnings[0].find("holds 2 DICOM series"), std::string::npos);
  // The value of slice k is 100 k - 1000 HU (after rescale) everywhere: the
  // slices come out in position order whatever the file names.
  for (int k = 0; k < 6; ++k)
  {
    EXPECT_EQ(largest.intensities[static_cast<size_t>(k) * 120 + 17], 100.0f * k - 1000.0f) << k;
  }
  EXPECT_NEAR(largest.spacingMm[2], 2.5, 1e-6);
  const CTVolume small = readCTVolume(folder, { "1.2.826.0.1.3680043.2.1125.1002" });
  EXPECT_EQ(small.dims[2], 3);
  EXPECT_TRUE(small.warnings.empty());
  EXPECT_EQ(messageOf(folder + "/../DicomTwoSeries"), "no error");
  try
  {
    readCTVolume(folder, { "9.9.9" });
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_EQ(
      std::string(e.what()), "'" + folder + "': no DICOM series with UID '9.9.9' in the folder");
  }
}

TEST(CTVolumeIO, ErrorsNameTheFileAndTheProblem)
{
  EXPECT_EQ(messageOf(out + "/nothing.nii"), "'" + out + "/nothing.nii': no such file or folder");

  const std::string text = std::string(VIMLOP_TEST_DATA_DIR) + "/Bad/notes.txt";
  EXPECT_NE(messageOf(text).find("unsupported CT file type"), std::string::npos);

  const std::string truncated = std::string(VIMLOP_TEST_DATA_DIR) + "/Bad/truncated.nii";
  EXPECT_EQ(messageOf(truncated),
    "'" + truncated + "': the file is truncated (1376 bytes, the header promises 4448)");

  // A slice, a single voxel, a column: one voxel thick is not a volume.
  for (const auto& [name, dims, size] :
    { std::make_tuple("flat", std::array<int, 3>{ 7, 5, 1 }, "7 x 5 x 1"),
      std::make_tuple("voxel", std::array<int, 3>{ 1, 1, 1 }, "1 x 1 x 1"),
      std::make_tuple("column", std::array<int, 3>{ 1, 6, 9 }, "1 x 6 x 9") })
  {
    CTVolume thin = makeVolume();
    thin.dims = dims;
    thin.intensities.resize(thin.numberOfVoxels());
    const std::string path = out + "/" + name + ".nrrd";
    writeCTVolume(thin, path);
    EXPECT_EQ(messageOf(path),
      "'" + path + "': the image is " + size +
        " voxels; a 3-D CT volume needs at least 2 along each axis");
  }

  // Garbage with a NIfTI name.
  std::ofstream(out + "/garbage.nii") << "garbage";
  EXPECT_EQ(messageOf(out + "/garbage.nii").rfind("'" + out + "/garbage.nii': ", 0), 0u);

  // An empty folder holds no series.
  std::filesystem::create_directories(out + "/emptyfolder");
  EXPECT_EQ(
    messageOf(out + "/emptyfolder"), "'" + out + "/emptyfolder': the folder holds no DICOM series");

  EXPECT_THROW(writeCTVolume(makeVolume(), out + "/volume.png"), Error);
}

TEST(CTVolumeIO, GeometryNoCTHasIsRefused)
{
  // MetaImage headers written by hand: ITK reads each of them as given.
  std::ofstream(out + "/cube.raw", std::ios::binary) << std::string(2 * 4 * 4 * 4, '\0');
  auto header = [](const std::string& name, const std::string& geometry)
  {
    const std::string path = out + "/" + name + ".mhd";
    std::ofstream(path) << "ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\n"
                        << geometry << "ElementType = MET_SHORT\nElementDataFile = cube.raw\n";
    return path;
  };
  const std::string fine = header("fine", "ElementSpacing = 0.5 0.5 1.25\n");
  EXPECT_EQ(messageOf(fine), "no error");
  const std::string huge = header("huge-spacing", "ElementSpacing = 1e300 1 1\n");
  EXPECT_EQ(messageOf(huge),
    "'" + huge +
      "': the voxel spacing 1e+300 x 1 x 1 mm is not a CT's: each must be finite, positive and "
      "at most 100 mm");
  const std::string far = header("far-origin", "ElementSpacing = 1 1 1\nOffset = 1e308 0 0\n");
  EXPECT_EQ(messageOf(far),
    "'" + far +
      "': the origin (1e+308, 0, 0) mm is not finite or lies farther than 1 km from the "
      "scanner's");
  const std::string sheared =
    header("sheared", "ElementSpacing = 1 1 1\nTransformMatrix = 1 0 0 0.5 1 0 0 0 1\n");
  EXPECT_EQ(messageOf(sheared),
    "'" + sheared +
      "': the direction matrix is not orthonormal (its columns, the voxel axes, must be unit "
      "vectors at right angles)");
}

TEST(CTVolumeIO, ASmallFileCannotMakeTheReaderAllocateGigabytes)
{
  const auto write = [](const std::string& name, const std::string& header, std::size_t dataBytes)
  {
    const std::string path = out + "/" + name;
    std::ofstream(path, std::ios::binary) << header << std::string(dataBytes, '\x01');
    return path;
  };
  const std::string nrrd = "NRRD0004\ntype: short\ndimension: 3\nsizes: 1000 1000 1000\n";
  const std::string raw = write("promise-raw.nrrd", nrrd + "encoding: raw\nendian: little\n\n", 10);
  EXPECT_EQ(messageOf(raw),
    "'" + raw + "': the image data are cut short (10 bytes, the header promises 2000000000)");
  const std::string gzip =
    write("promise-gzip.nrrd", nrrd + "encoding: gzip\nendian: little\n\n", 20);
  EXPECT_EQ(messageOf(gzip),
    "'" + gzip +
      "': the header promises 2000000000 bytes of voxels, which 20 bytes of compressed data "
      "cannot hold; refusing to allocate them");
  const std::string mha = write("promise.mha",
    "ObjectType = Image\nNDims = 3\nDimSize = 1000 1000 1000\nElementType = MET_SHORT\n"
    "CompressedData = True\nCompressedDataSize = 20\nElementDataFile = LOCAL\n",
    20);
  EXPECT_EQ(messageOf(mha),
    "'" + mha +
      "': the header promises 2000000000 bytes of voxels, which 20 bytes of compressed data "
      "cannot hold; refusing to allocate them");
}

TEST(CTVolumeIO, AMetaImageCompressedSizeBeyondItsDataIsRefused)
{
  // MetaIO allocated the CompressedDataSize it read, 8 EiB here, before reading.
  const std::string path = out + "/compressed-size.mha";
  std::ofstream(path, std::ios::binary)
    << "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_SHORT\n"
    << "CompressedData = True\nCompressedDataSize = 9223372036854775807\n"
    << "ElementDataFile = LOCAL\n"
    << std::string(20, '\x01');
  EXPECT_EQ(messageOf(path),
    "'" + path +
      "': the header's CompressedDataSize (9223372036854775807 bytes) is more than the 20 bytes "
      "of data");
}

TEST(CTVolumeIO, AFileIsReadOnlyByTheReaderItsExtensionNames)
{
  // ITK's factory let GDCM parse a .nii file as DICOM, and GDCM aborted.
  std::string dicom(128, '\0');
  dicom += "DICM";
  dicom += std::string("\x02\x00\x00\x00OD\x00\x00\x04\x00\x00\x00\x76\x00\x00\x00", 16);
  const std::string path = out + "/dicom-inside.nii";
  std::ofstream(path, std::ios::binary) << dicom;
  EXPECT_EQ(messageOf(path),
    "'" + path +
      "': not a NIfTI-1 or NIfTI-2 header (it does not start with its size, 348 or 540)");
  // MetaIO read "ElementDataFile\0..." as its key; the header is text.
  const std::string nul = out + "/nul-key.mha";
  std::ofstream(nul, std::ios::binary)
    << "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_SHORT\n"
    << std::string("ElementDataFile\0 = LOCAL\n", 26) << std::string(16, '\x01');
  EXPECT_EQ(messageOf(nul), "'" + nul + "': header line 5 holds bytes that are not text");
  // Far down the header too: the check stopped at line 200, MetaIO did not,
  // and overflowed a buffer splitting a data file name of control bytes.
  const std::string far = out + "/far-control-bytes.mha";
  std::ofstream(far, std::ios::binary)
    << "ObjectType = Image\nNDims = 3\n"
    << std::string(250, '\n')
    << "DimSize = 2 2 2\nElementType = MET_SHORT\nElementDataFile = LOC\x19\x19 AL\n"
    << std::string(16, '\x01');
  EXPECT_EQ(messageOf(far), "'" + far + "': header line 255 holds bytes that are not text");
  // MetaIO read on past an ElementDataFile that came too early, into the data.
  const std::string early = out + "/early-data-file.mha";
  std::ofstream(early, std::ios::binary)
    << "ObjectType = Image\nElementDataFile = LOCAL\nNDims = 44444444444\n";
  EXPECT_EQ(messageOf(early),
    "'" + early +
      "': the header gives ElementDataFile before its DimSize (ElementDataFile is a MetaImage "
      "header's last field)");
  // MetaIO matched an unknown key by its start, and overflowed a buffer copying it.
  const std::string unknown = out + "/unknown-key.mha";
  std::ofstream(unknown, std::ios::binary)
    << "ObjectType = Image\nNDims = 3\nC = 3\nDimSize = 2 2 2\nElementType = MET_SHORT\n"
    << "ElementDataFile = LOCAL\n"
    << std::string(16, '\x01');
  EXPECT_EQ(messageOf(unknown),
    "'" + unknown + "': header line 3 has the key 'C', which MetaImage does not define");
  // A negative dimension count: MetaIO's reading of the sizes did not end.
  const std::string negative = out + "/negative-ndims.mha";
  std::ofstream(negative) << "ObjectType = Image\nNDims = -2\nDimSize = 10 10 10\n"
                          << "ElementType = MET_SHORT\nElementDataFile = LOCAL\n";
  EXPECT_EQ(messageOf(negative),
    "'" + negative + "': the header's NDims is '-2', not a count of 1 to 4 dimensions");
  // One data file per slice: MetaIO divided by the pattern's step of 0.
  const std::string pattern = out + "/pattern.mhd";
  std::ofstream(pattern) << "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\n"
                         << "ElementType = MET_SHORT\nElementDataFile = slice%03d.raw 0 1 0\n";
  EXPECT_EQ(messageOf(pattern),
    "'" + pattern +
      "': the header lists one data file per slice (LIST or a pattern); VIMLOP reads MetaImage "
      "volumes whose data are in one file");
}

TEST(CTVolumeIO, ANiftiOrientationThatIsNotFiniteIsRefusedBeforeITKReadsIt)
{
  // ITK took the SVD of the orientation, which aborted the process on a NaN.
  CTVolume volume;
  volume.dims = { 3, 3, 3 };
  volume.intensities.assign(27, -1000.0f);
  const std::string path = out + "/nan-sform.nii";
  writeCTVolume(volume, path);
  std::fstream file(path, std::ios::binary | std::ios::in | std::ios::out);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  file.seekp(280); // srow_x[0]
  file.write(reinterpret_cast<const char*>(&nan), sizeof(nan));
  file.close();
  const std::string huge = out + "/huge-qoffset.nii";
  writeCTVolume(volume, huge);
  std::fstream hugeFile(huge, std::ios::binary | std::ios::in | std::ios::out);
  const float far = 3e38f;
  hugeFile.seekp(268); // qoffset_x: ITK's SVD of such an orientation did not return
  hugeFile.write(reinterpret_cast<const char*>(&far), sizeof(far));
  hugeFile.close();
  EXPECT_NE(messageOf(huge).find("are not finite or not those of a scan"), std::string::npos);
  EXPECT_EQ(messageOf(path),
    "'" + path +
      "': the header's voxel sizes or orientation (pixdim, qform, sform) are not finite or not "
      "those of a scan");
}

namespace
{

/// A NIfTI-2 file of 2 x 2 x 2 int16 voxels of 1 mm, its orientation by
/// quaternion and sform, with srow_x[0] as given.
std::string writeNifti2(const std::string& name, double srowX0)
{
  std::string header(544, '\0');
  const auto put = [&](std::size_t at, const void* value, std::size_t bytes)
  { std::memcpy(&header[at], value, bytes); };
  const std::int32_t size = 540;
  put(0, &size, 4);
  put(4, "n+2\0\r\n\032\n", 8);
  const std::int16_t datatype = 4; // int16
  const std::int16_t bitpix = 16;
  put(12, &datatype, 2);
  put(14, &bitpix, 2);
  const std::int64_t dim[8] = { 3, 2, 2, 2, 1, 1, 1, 1 };
  put(16, dim, sizeof(dim));
  const double pixdim[8] = { 1, 1, 1, 1, 1, 1, 1, 1 };
  put(104, pixdim, sizeof(pixdim));
  const std::int64_t voxOffset = 544;
  put(168, &voxOffset, 8);
  const double slope = 1.0;
  put(176, &slope, 8);
  const std::int32_t codes[2] = { 1, 1 }; // qform_code, sform_code
  put(344, codes, sizeof(codes));
  const double srow[12] = { srowX0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 };
  put(400, srow, sizeof(srow));
  const std::string path = out + "/" + name + ".nii";
  std::ofstream(path, std::ios::binary) << header << std::string(16, '\0');
  return path;
}

} // namespace

TEST(CTVolumeIO, ANifti2OrientationThatIsNotFiniteIsRefusedBeforeITKReadsIt)
{
  const std::string nan = writeNifti2("nan-sform-2", std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(messageOf(nan),
    "'" + nan +
      "': the header's voxel sizes or orientation (pixdim, qform, sform) are not finite or not "
      "those of a scan");
  const std::string far = writeNifti2("far-sform-2", 1e300);
  EXPECT_EQ(messageOf(far),
    "'" + far +
      "': the header's voxel sizes or orientation (pixdim, qform, sform) are not finite or not "
      "those of a scan");
  // The same header with a scan's values passes the check, and this ITK
  // says what it cannot read.
  const std::string finite = writeNifti2("finite-sform-2", 1.0);
  EXPECT_EQ(messageOf(finite),
    "'" + finite +
      "': a NIfTI-2 file, which this build's ITK (5.2) does not read; save the volume as NIfTI-1 "
      "(.nii, .nii.gz), NRRD or MetaImage");
}
