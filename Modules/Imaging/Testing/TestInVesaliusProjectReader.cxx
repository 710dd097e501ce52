#include "InVesaliusTestFiles.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/InVesaliusProjectReader.h>

#include <gtest/gtest.h>

#include <filesystem>

using namespace vimlop;

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;
const std::string cranium = "/usr/share/doc/invesalius-examples/examples/Cranium.inv3";

std::string messageOf(const std::string& path)
{
  try
  {
    readInVesaliusProject(path);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(InVesaliusProjectReader, ReadsVoxelsInXYZOrderWithTheDocumentedFrame)
{
  const int nx = 5, ny = 4, nz = 3;
  const std::string path = fixtures::writeProject(out + "/small.inv3",
    { { "tmpabc/main.plist", fixtures::plist(nx, ny, nz) }, { "tmpabc/surface_0.vtp", "ignored" },
      { "tmpabc/matrix.dat", fixtures::matrix(nx, ny, nz) } });
  const CTVolume v = readInVesaliusProject(path);
  EXPECT_EQ(v.dims, (std::array<int, 3>{ nx, ny, nz }));
  EXPECT_EQ(v.spacingMm, (std::array<double, 3>{ 0.5, 0.75, 2.0 }));
  EXPECT_EQ(v.format, "InVesalius project");
  for (int z = 0; z < nz; ++z)
  {
    for (int y = 0; y < ny; ++y)
    {
      for (int x = 0; x < nx; ++x)
      {
        ASSERT_EQ(v.intensities[x + nx * (y + ny * z)], fixtures::testVoxel(x, y, z));
      }
    }
  }
  // y (rows) grows anterior, i.e. towards -y in LPS; the last row sits at y = 0.
  EXPECT_EQ(v.indexToPhysical({ 0, ny - 1.0, 0 }), (std::array<double, 3>{ 0.0, 0.0, 0.0 }));
  EXPECT_EQ(v.indexToPhysical({ 1, 0, 1 }), (std::array<double, 3>{ 0.5, (ny - 1) * 0.75, 2.0 }));
  EXPECT_EQ(v.direction, (std::array<double, 9>{ 1, 0, 0, 0, -1, 0, 0, 0, 1 }));
}

TEST(InVesaliusProjectReader, ReadsTheRealCranium)
{
  ASSERT_TRUE(std::filesystem::exists(cranium))
    << "install Debian's invesalius-examples (make test does it)";
  const CTVolume v = readInVesaliusProject(cranium);
  EXPECT_EQ(v.dims, (std::array<int, 3>{ 256, 256, 108 }));
  EXPECT_NEAR(v.spacingMm[0], 0.957, 1e-3);
  EXPECT_NEAR(v.spacingMm[1], 0.957, 1e-3);
  EXPECT_NEAR(v.spacingMm[2], 1.5, 1e-9);
  const auto [lo, hi] = std::minmax_element(v.intensities.begin(), v.intensities.end());
  EXPECT_EQ(*lo, -1024.0f);
  EXPECT_EQ(*hi, 2986.0f); // main.plist claims 3033, the voxels say otherwise
  // Anatomy behind the documented orientation. Counts of tissue voxels (above
  // -500 HU): the head rest lies behind the head, at low row index j, while
  // only the nose reaches the highest rows; the skull narrows to its vertex
  // at high slice index k (superior).
  auto tissue = [&](int x, int y, int z)
  { return v.intensities[x + 256 * (y + 256 * z)] > -500.0f; };
  long lowRows = 0, highRows = 0, lowSlices = 0, highSlices = 0;
  int noseSlice = -1, noseRow = -1;
  for (int z = 0; z < 108; ++z)
  {
    for (int y = 0; y < 256; ++y)
    {
      for (int x = 0; x < 256; ++x)
      {
        if (!tissue(x, y, z))
        {
          continue;
        }
        lowRows += y < 20;
        highRows += y >= 236;
        lowSlices += z < 10;
        highSlices += z >= 98;
        if (x > 100 && x < 156 && y > noseRow)
        {
          noseRow = y;
          noseSlice = z;
        }
      }
    }
  }
  EXPECT_GT(lowRows, 10 * highRows);
  EXPECT_GT(lowSlices, 3 * highSlices);
  // The nose tip: the most anterior tissue, in the lower third of the head.
  EXPECT_GT(noseRow, 236);
  EXPECT_LT(noseSlice, 40);
}

TEST(InVesaliusProjectReader, ErrorsNameTheFileAndTheProblem)
{
  EXPECT_EQ(messageOf(out + "/missing.inv3"), "'" + out + "/missing.inv3': cannot open the file");

  const std::string noPlist =
    fixtures::writeProject(out + "/noplist.inv3", { { "matrix.dat", fixtures::matrix(2, 2, 2) } });
  EXPECT_EQ(messageOf(noPlist),
    "'" + noPlist + "': not an InVesalius project (no main.plist in the archive)");

  const std::string noMatrix =
    fixtures::writeProject(out + "/nomatrix.inv3", { { "main.plist", fixtures::plist(2, 2, 2) } });
  EXPECT_EQ(
    messageOf(noMatrix), "'" + noMatrix + "': the archive has no 'matrix.dat' named by main.plist");

  const std::string wrongSize = fixtures::writeProject(out + "/wrongsize.inv3",
    { { "main.plist", fixtures::plist(3, 2, 2) }, { "matrix.dat", fixtures::matrix(2, 2, 2) } });
  EXPECT_EQ(messageOf(wrongSize),
    "'" + wrongSize + "': 'matrix.dat' holds 16 bytes but the shape 2x2x3 needs 24");

  const std::string floats = fixtures::writeProject(out + "/float.inv3",
    { { "main.plist", fixtures::plist(2, 2, 2, "float64") },
      { "matrix.dat", fixtures::matrix(2, 2, 2) } });
  EXPECT_EQ(messageOf(floats),
    "'" + floats + "': unsupported matrix type 'float64' (InVesalius volumes are int16)");

  const std::string badSpacing = fixtures::writeProject(out + "/spacing.inv3",
    { { "main.plist",
        fixtures::plist(2, 2, 2, "int16", "<real>1</real><real>-1</real><real>1</real>") },
      { "matrix.dat", fixtures::matrix(2, 2, 2) } });
  EXPECT_EQ(messageOf(badSpacing),
    "'" + badSpacing + "': main.plist has no valid spacing (three positive numbers)");

  const std::string notXml = fixtures::writeProject(out + "/notxml.inv3",
    { { "main.plist", "this is not xml" }, { "matrix.dat", fixtures::matrix(2, 2, 2) } });
  EXPECT_EQ(messageOf(notXml), "'" + notXml + "': main.plist is not a property list dictionary");

  const std::string garbage = std::string(VIMLOP_TEST_DATA_DIR) + "/Bad/corrupt.inv3";
  EXPECT_EQ(
    messageOf(garbage), "'" + garbage + "': not an InVesalius project (invalid tar header)");
}

TEST(InVesaliusProjectReader, TruncatedArchivesAreReported)
{
  const std::string full = fixtures::writeProject(out + "/full.inv3",
    { { "main.plist", fixtures::plist(40, 40, 40) },
      { "matrix.dat", fixtures::matrix(40, 40, 40) } });
  // Cut the compressed file in half: the matrix member ends early.
  const auto size = std::filesystem::file_size(full);
  std::filesystem::copy_file(
    full, out + "/cut.inv3", std::filesystem::copy_options::overwrite_existing);
  std::filesystem::resize_file(out + "/cut.inv3", size / 2);
  const std::string message = messageOf(out + "/cut.inv3");
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
}

TEST(InVesaliusProjectReader, HeadersPromisingHugeMembersAllocateNothing)
{
  // A tar header claiming a 3 GiB matrix followed by 1 KiB: the reader must
  // report the truncation, not reserve the 3 GiB first.
  std::string header = fixtures::tarMember("matrix.dat", std::string(1024, 'x')).substr(0, 512);
  std::snprintf(&header[124], 12, "%011llo", 3ull << 30);
  header[135] = ' ';
  const std::string path =
    fixtures::writeProject(out + "/promises.inv3", { { "main.plist", fixtures::plist(2, 2, 2) } });
  // Rewrite with the forged member appended after main.plist.
  std::string tar =
    fixtures::tarMember("main.plist", fixtures::plist(2, 2, 2)) + header + std::string(1024, 'x');
  gzFile file = gzopen(path.c_str(), "wb");
  gzwrite(file, tar.data(), static_cast<unsigned>(tar.size()));
  gzclose(file);
  EXPECT_EQ(messageOf(path), "'" + path + "': archive is truncated inside 'matrix.dat'");
}
