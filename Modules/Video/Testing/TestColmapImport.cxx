#include "ColmapBinaryWriting.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Video/ColmapImport.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <filesystem>
#include <fstream>

using namespace vimlop;
using fixtures::put;
using fixtures::putImage;
namespace fs = std::filesystem;

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;

std::string freshFolder(const std::string& name)
{
  const std::string folder = out + "/" + name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

// The model written below, as COLMAP stores it: image 12 'frameA.png' with
// camera 7 (SIMPLE_RADIAL), image 11 'frameB.png' with camera 3 (PINHOLE),
// point 100 seen by both, point 101 by image 11 only.
const Eigen::Quaterniond qA(0.9, 0.1, -0.2, 0.3);
const Eigen::Vector3d tA(0.5, -1.0, 2.0);
const Eigen::Quaterniond qB(1.0, 0.0, 0.0, 0.0);
const Eigen::Vector3d tB(-1.0, 0.0, 0.25);

void writeText(
  const std::string& folder, const std::string& pinholeModel = "PINHOLE", int pointImage = 11)
{
  std::ofstream(folder + "/cameras.txt") << "# Camera list with one line of data per camera:\n"
                                         << "3 " << pinholeModel << " 320 240 200 210 160 120\n"
                                         << "7 SIMPLE_RADIAL 320 240 205 161 121 -0.05\n";
  const Eigen::Quaterniond a = qA.normalized();
  std::ofstream images(folder + "/images.txt");
  images << "# Image list with two lines of data per image:\n";
  images << "12 " << a.w() << " " << a.x() << " " << a.y() << " " << a.z() << " " << tA.x() << " "
         << tA.y() << " " << tA.z() << " 7 frameA.png\n";
  images << "10.5 20.5 100 30 40 -1\n";
  images << "11 1 0 0 0 " << tB.x() << " " << tB.y() << " " << tB.z() << " 3 frameB.png\n";
  images << "11.5 22.5 100 50.5 60.5 101\n";
  std::ofstream(folder + "/points3D.txt")
    << "# 3D point list with one line of data per point:\n"
    << "100 1 2 10 200 100 90 0.3 12 0 " << pointImage << " 0\n"
    << "101 -1 0.5 12 10 20 30 0.2 11 1 12 1\n";
}

void writeBinary(const std::string& folder, int pinholeModelId = 1)
{
  {
    std::ofstream f(folder + "/cameras.bin", std::ios::binary);
    put<std::uint64_t>(f, 2);
    put<std::uint32_t>(f, 3);
    put<std::int32_t>(f, pinholeModelId);
    put<std::uint64_t>(f, 320);
    put<std::uint64_t>(f, 240);
    for (double p : { 200.0, 210.0, 160.0, 120.0 })
    {
      put(f, p);
    }
    put<std::uint32_t>(f, 7);
    put<std::int32_t>(f, 2);
    put<std::uint64_t>(f, 320);
    put<std::uint64_t>(f, 240);
    for (double p : { 205.0, 161.0, 121.0, -0.05 })
    {
      put(f, p);
    }
  }
  {
    std::ofstream f(folder + "/images.bin", std::ios::binary);
    put<std::uint64_t>(f, 2);
    putImage(f, 12, qA, tA, 7, "frameA.png",
      { { { 10.5, 20.5 }, 100 }, { { 30, 40 }, std::numeric_limits<std::uint64_t>::max() } });
    putImage(f, 11, qB, tB, 3, "frameB.png", { { { 11.5, 22.5 }, 100 }, { { 50.5, 60.5 }, 101 } });
  }
  {
    std::ofstream f(folder + "/points3D.bin", std::ios::binary);
    put<std::uint64_t>(f, 2);
    auto point = [&](std::uint64_t id, const Eigen::Vector3d& xyz,
                   const std::vector<std::uint8_t>& rgb,
                   const std::vector<std::pair<std::uint32_t, std::uint32_t>>& track)
    {
      put(f, id);
      for (int a = 0; a < 3; ++a)
      {
        put(f, xyz[a]);
      }
      for (std::uint8_t c : rgb)
      {
        put(f, c);
      }
      put(f, 0.25);
      put<std::uint64_t>(f, track.size());
      for (const auto& [image, index] : track)
      {
        put(f, image);
        put(f, index);
      }
    };
    point(100, { 1, 2, 10 }, { 200, 100, 90 }, { { 12, 0 }, { 11, 0 } });
    point(101, { -1, 0.5, 12 }, { 10, 20, 30 }, { { 11, 1 }, { 12, 1 } });
  }
}

std::string messageOf(const std::string& folder, ColmapFormat format = ColmapFormat::Automatic)
{
  try
  {
    readColmapModel(folder, format);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

void expectTheModel(const SfmReconstruction& r)
{
  EXPECT_EQ(r.source, "colmap");
  ASSERT_EQ(r.frames.size(), 2u);
  // Sorted by name: frameA (image 12) first.
  EXPECT_EQ(r.frames[0].name, "frameA.png");
  EXPECT_EQ(r.frames[1].name, "frameB.png");
  // COLMAP's world-to-camera (q, t) becomes camera-to-SfM: axes R^T, centre -R^T t.
  const Eigen::Matrix3d rA = qA.normalized().toRotationMatrix();
  EXPECT_TRUE(r.frames[0].cameraToSfm.rotation.isApprox(rA.transpose(), 1e-5));
  EXPECT_TRUE(r.frames[0].cameraToSfm.centre.isApprox(-rA.transpose() * tA, 1e-5));
  EXPECT_TRUE(r.frames[1].cameraToSfm.centre.isApprox(-tB, 1e-12));
  // Pixel centres move from COLMAP's 0.5 to VIMLOP's 0.
  const PinholeCamera& pinhole = r.frames[1].intrinsics;
  EXPECT_EQ(pinhole.fx, 200.0);
  EXPECT_EQ(pinhole.fy, 210.0);
  EXPECT_EQ(pinhole.cx, 159.5);
  EXPECT_EQ(pinhole.cy, 119.5);
  EXPECT_EQ(pinhole.distortion.size(), 0);
  const PinholeCamera& radial = r.frames[0].intrinsics;
  EXPECT_EQ(radial.fx, 205.0);
  EXPECT_EQ(radial.fy, 205.0);
  EXPECT_EQ(radial.cx, 160.5);
  ASSERT_EQ(radial.distortion.size(), 4);
  EXPECT_EQ(radial.distortion[0], -0.05);
  EXPECT_EQ(radial.distortion[1], 0.0);
  ASSERT_EQ(r.points.size(), 2u);
  const SfmReconstruction::Point& p = r.points[0];
  EXPECT_EQ(p.position, Eigen::Vector3d(1, 2, 10));
  EXPECT_EQ(p.colour, Eigen::Vector3i(200, 100, 90));
  ASSERT_EQ(p.observations.size(), 2u);
  EXPECT_EQ(p.observations[0].frame, 0);
  EXPECT_EQ(p.observations[0].pixel, Eigen::Vector2d(10.0, 20.0));
  EXPECT_EQ(p.observations[1].frame, 1);
  EXPECT_EQ(p.observations[1].pixel, Eigen::Vector2d(11.0, 22.0));
  // Covariances from the two views' geometry.
  EXPECT_GT(p.covariance(2, 2), p.covariance(0, 0));
}

} // namespace

TEST(ColmapImport, ReadsTextModels)
{
  const std::string folder = freshFolder("colmap-text");
  writeText(folder);
  expectTheModel(readColmapModel(folder));
}

TEST(ColmapImport, ReadsBinaryModels)
{
  const std::string folder = freshFolder("colmap-binary");
  writeBinary(folder);
  expectTheModel(readColmapModel(folder, ColmapFormat::Binary));
}

TEST(ColmapImport, OpenCVModelKeepsItsDistortion)
{
  const std::string folder = freshFolder("colmap-opencv");
  writeText(folder);
  std::ofstream(folder + "/cameras.txt")
    << "3 OPENCV 320 240 200 210 160 120 -0.1 0.01 0.001 -0.002\n"
    << "7 PINHOLE 320 240 205 205 161 121\n";
  const SfmReconstruction r = readColmapModel(folder, ColmapFormat::Text);
  const PinholeCamera& k = r.frames[1].intrinsics;
  ASSERT_EQ(k.distortion.size(), 4);
  EXPECT_EQ(k.distortion, Eigen::Vector4d(-0.1, 0.01, 0.001, -0.002));
  EXPECT_EQ(k.fy, 210.0);
}

TEST(ColmapImport, OpenCVFisheyeModelBecomesAFisheyeLensWithItsFourCoefficients)
{
  const std::string folder = freshFolder("colmap-opencv-fisheye");
  writeText(folder);
  std::ofstream(folder + "/cameras.txt")
    << "3 OPENCV_FISHEYE 320 240 200 210 160 120 0.05 -0.01 0.002 -0.0005\n"
    << "7 PINHOLE 320 240 205 205 161 121\n";
  const SfmReconstruction r = readColmapModel(folder, ColmapFormat::Text);
  const PinholeCamera& fisheye = r.frames[1].intrinsics;
  EXPECT_EQ(fisheye.lensModel, LensModel::Fisheye);
  EXPECT_EQ(fisheye.distortion, Eigen::Vector4d(0.05, -0.01, 0.002, -0.0005));
  EXPECT_EQ(fisheye.fy, 210.0);
  EXPECT_EQ(fisheye.cx, 159.5);
  EXPECT_EQ(r.frames[0].intrinsics.lensModel, LensModel::RadialTangential);
}

TEST(ColmapImport, FollowsTheGivenFrameNames)
{
  const std::string folder = freshFolder("colmap-frames");
  writeText(folder);
  std::vector<std::string> warnings;
  const SfmReconstruction r =
    readColmapModel(folder, ColmapFormat::Text, { "frameB.png", "frameC.png" }, 0.5, &warnings);
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.frames[0].name, "frameB.png");
  EXPECT_TRUE(r.frames[0].registered);
  EXPECT_FALSE(r.frames[1].registered);
  // Points keep only what frameB sees, and need two observations.
  EXPECT_TRUE(r.points.empty());
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_EQ(
    warnings[0], "COLMAP model: dropped 1 image(s) not among the frames (first: 'frameA.png')");
  EXPECT_EQ(warnings[1], "COLMAP model: frame 'frameC.png' is not registered");
  EXPECT_EQ(warnings[2], "COLMAP model: dropped 2 observation(s) in images not among the frames");
}

TEST(ColmapImport, RejectsUnknownAndUnsupportedCameraModels)
{
  const std::string folder = freshFolder("colmap-unknown-model");
  writeText(folder, "MAGIC_LENS");
  EXPECT_EQ(messageOf(folder),
    "'" + folder +
      "/cameras.txt': unknown camera model 'MAGIC_LENS' (supported: SIMPLE_PINHOLE, PINHOLE, "
      "SIMPLE_RADIAL, RADIAL, OPENCV, OPENCV_FISHEYE, FULL_OPENCV)");
  writeText(folder, "FOV");
  EXPECT_NE(
    messageOf(folder).find("cameras.txt': unsupported camera model 'FOV'"), std::string::npos);
  const std::string binary = freshFolder("colmap-unknown-model-bin");
  writeBinary(binary, 42);
  EXPECT_EQ(messageOf(binary),
    "'" + binary +
      "/cameras.bin': unknown camera model id 42 (supported: SIMPLE_PINHOLE, PINHOLE, "
      "SIMPLE_RADIAL, RADIAL, OPENCV, OPENCV_FISHEYE, FULL_OPENCV)");
}

TEST(ColmapImport, RejectsDanglingIds)
{
  const std::string folder = freshFolder("colmap-dangling");
  writeText(folder, "PINHOLE", 99);
  EXPECT_EQ(messageOf(folder),
    "'" + folder +
      "/points3D.txt': point 100 is observed by image 99, which images.txt does not hold (dangling "
      "id)");
  // An image of a camera that does not exist.
  writeText(folder);
  std::ofstream(folder + "/cameras.txt") << "3 PINHOLE 320 240 200 210 160 120\n";
  EXPECT_EQ(messageOf(folder),
    "'" + folder +
      "/images.txt': image 'frameA.png' uses camera 7, which cameras.txt does not define");
}

TEST(ColmapImport, RejectsMissingAndTruncatedFiles)
{
  EXPECT_EQ(messageOf(out + "/no-such-model"),
    "'" + out +
      "/no-such-model': no such folder (expected a COLMAP sparse model folder such as sparse/0)");
  const std::string empty = freshFolder("colmap-empty");
  EXPECT_EQ(
    messageOf(empty), "'" + empty + "': not a COLMAP sparse model (no cameras.bin or cameras.txt)");
  const std::string truncated = freshFolder("colmap-truncated");
  writeBinary(truncated);
  fs::resize_file(truncated + "/images.bin", 60);
  EXPECT_NE(messageOf(truncated).find("images.bin': the file is truncated"), std::string::npos)
    << messageOf(truncated);
}

TEST(ColmapImport, PinholeParametersUseColmapPixelCentres)
{
  PinholeCamera k;
  k.fx = 200.0;
  k.fy = 210.0;
  k.cx = 159.5;
  k.cy = 119.5;
  EXPECT_EQ(colmapPinholeParameters(k), "200,210,160,120");
}

TEST(ColmapImport, ReadsTheFullOpenCVModelAsOpenCVsRationalModel)
{
  const std::string folder = freshFolder("colmap-full-opencv");
  writeText(folder);
  // fx, fy, cx, cy, then k1, k2, p1, p2, k3, k4, k5, k6 in COLMAP's order, which is OpenCV's.
  std::ofstream(folder + "/cameras.txt")
    << "3 FULL_OPENCV 320 240 200 210 160 120 -0.3 0.1 0.001 0.002 -0.02 0.01 0.003 0.0004\n"
    << "7 SIMPLE_RADIAL 320 240 205 161 121 -0.05\n";
  const SfmReconstruction r = readColmapModel(folder, ColmapFormat::Text);
  const PinholeCamera& k = r.frames[1].intrinsics; // frameB, camera 3
  EXPECT_EQ(k.lensModel, LensModel::RadialTangential);
  ASSERT_EQ(k.distortion.size(), 8);
  EXPECT_DOUBLE_EQ(k.distortion[0], -0.3);
  EXPECT_DOUBLE_EQ(k.distortion[3], 0.002);
  EXPECT_DOUBLE_EQ(k.distortion[4], -0.02);
  EXPECT_DOUBLE_EQ(k.distortion[7], 0.0004);
  EXPECT_DOUBLE_EQ(k.fy, 210.0);
  EXPECT_DOUBLE_EQ(k.cx, 159.5);
}
