#include <vimlop/Core/Error.h>
#include <vimlop/Video/SfmReconstruction.h>
#include <vimlop/Video/SfmReconstructionIO.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <Eigen/Eigenvalues>

#include <fstream>

using namespace vimlop;

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;

PinholeCamera camera()
{
  PinholeCamera k;
  k.fx = 200.0;
  k.fy = 210.0;
  k.cx = 159.5;
  k.cy = 119.5;
  k.widthPx = 320;
  k.heightPx = 240;
  return k;
}

/// Two cameras `baseline` apart along x, looking down +z, and a point 10 units ahead.
SfmReconstruction twoViews(double baseline)
{
  SfmReconstruction r;
  for (int c = 0; c < 2; ++c)
  {
    SfmReconstruction::Frame f;
    f.name = "frame" + std::to_string(c) + ".png";
    f.registered = true;
    f.intrinsics = camera();
    f.cameraToSfm.centre = Eigen::Vector3d(c * baseline, 0.0, 0.0);
    r.frames.push_back(f);
  }
  SfmReconstruction::Point p;
  p.position = Eigen::Vector3d(0.5 * baseline, 0.0, 10.0);
  for (int c = 0; c < 2; ++c)
  {
    p.observations.push_back(
      { c, r.frames[c].intrinsics.project(r.frames[c].cameraToSfm.worldToCamera(p.position)) });
  }
  p.colour = Eigen::Vector3i(200, 100, 90);
  r.points.push_back(p);
  return r;
}

std::string readMessage(const std::string& path)
{
  try
  {
    readSfmReconstruction(path);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(SfmReconstruction, TriangulationCovarianceIsLongAlongTheRays)
{
  SfmReconstruction r = twoViews(1.0);
  r.computeCovariances(0.5);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(r.points[0].covariance);
  // Largest axis along the viewing direction (z), much longer than across.
  EXPECT_GT(std::abs(eigen.eigenvectors().col(2).z()), 0.99);
  EXPECT_GT(eigen.eigenvalues()[2], 50.0 * eigen.eigenvalues()[1]);
  // Across the rays: about (depth x sigma / f)^2 / 2 for two views.
  EXPECT_NEAR(r.points[0].covariance(0, 0), std::pow(10.0 * 0.5 / 200.0, 2) / 2.0, 1e-5);
  EXPECT_NEAR(r.points[0].reprojectionErrorPx, 0.0, 1e-9);
  // A wider baseline shortens it.
  SfmReconstruction wide = twoViews(5.0);
  wide.computeCovariances(0.5);
  EXPECT_LT(wide.points[0].covariance(2, 2), 0.1 * r.points[0].covariance(2, 2));
  // Parallel rays (the same camera twice) carry no depth: a large covariance.
  SfmReconstruction same = twoViews(0.0);
  same.computeCovariances(0.5);
  EXPECT_GE(same.points[0].covariance(2, 2), 99.0);
}

TEST(SfmReconstruction, FileKeepsEverything)
{
  SfmReconstruction r = twoViews(1.0);
  r.source = "colmap";
  r.trackerScale = 0.52;
  r.frames[1].cameraToSfm.rotation =
    Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  SfmReconstruction::Frame unregistered;
  unregistered.name = "frame2.png";
  unregistered.intrinsics = camera();
  r.frames.push_back(unregistered);
  r.computeCovariances(0.4);
  const std::string path = out + "/sfm-roundtrip.json";
  writeSfmReconstruction(r, path);
  const SfmReconstruction back = readSfmReconstruction(path);
  EXPECT_EQ(back.source, "colmap");
  EXPECT_EQ(back.trackerScale, 0.52);
  ASSERT_EQ(back.frames.size(), 3u);
  EXPECT_EQ(back.numberOfRegisteredFrames(), 2);
  EXPECT_EQ(back.frames[2].name, "frame2.png");
  EXPECT_TRUE(
    back.frames[1].cameraToSfm.rotation.isApprox(r.frames[1].cameraToSfm.rotation, 1e-15));
  EXPECT_EQ(back.frames[1].intrinsics.fy, 210.0);
  ASSERT_EQ(back.points.size(), 1u);
  EXPECT_EQ(back.points[0].position, r.points[0].position);
  EXPECT_TRUE(back.points[0].covariance.isApprox(r.points[0].covariance, 1e-15));
  EXPECT_EQ(back.points[0].colour, r.points[0].colour);
  ASSERT_EQ(back.points[0].observations.size(), 2u);
  EXPECT_EQ(back.points[0].observations[1].frame, 1);
  EXPECT_EQ(back.points[0].observations[1].pixel, r.points[0].observations[1].pixel);
}

TEST(SfmReconstruction, BadFilesAreNamedWithTheProblem)
{
  EXPECT_EQ(readMessage(out + "/no-such-sfm.json"),
    "'" + out + "/no-such-sfm.json': no such file or not readable");
  const std::string notJson = out + "/sfm-not-json.json";
  std::ofstream(notJson) << "frames: 3";
  EXPECT_EQ(readMessage(notJson), "'" + notJson + "': not a JSON file");
  const std::string other = out + "/sfm-other.json";
  std::ofstream(other) << R"({"format": "something-else"})";
  EXPECT_EQ(
    readMessage(other), "'" + other + "': not a VIMLOP SfM file (no \"format\": \"vimlop-sfm\")");
  // Found by fuzzing: a "format" that is no string threw a JSON type error.
  const std::string listFormat = out + "/sfm-list-format.json";
  std::ofstream(listFormat) << R"({"format": ["vimlop-sfm"]})";
  EXPECT_EQ(readMessage(listFormat),
    "'" + listFormat + "': not a VIMLOP SfM file (no \"format\": \"vimlop-sfm\")");
  // A frame index beyond int (casting it would be undefined behaviour).
  const std::string hugeIndex = out + "/sfm-huge-index.json";
  std::ofstream(hugeIndex)
    << R"({"format": "vimlop-sfm", "frames": [], "points": [{"position": [0, 0, 1],
          "covariance": [1, 0, 0, 1, 0, 1], "observations": [[1e300, 5, 5]]}]})";
  EXPECT_NE(
    readMessage(hugeIndex).find("expected a whole number for a frame index"), std::string::npos)
    << readMessage(hugeIndex);
  // A point observed by a frame that does not exist.
  SfmReconstruction r = twoViews(1.0);
  r.points[0].observations[1].frame = 5;
  const std::string dangling = out + "/sfm-dangling.json";
  writeSfmReconstruction(r, dangling);
  EXPECT_EQ(readMessage(dangling),
    "'" + dangling + "': SfM point 0 is observed by frame 5, which does not exist");
  const std::string truncated = out + "/sfm-missing-entry.json";
  std::ofstream(truncated) << R"({"format": "vimlop-sfm", "frames": []})";
  EXPECT_NE(readMessage(truncated).find("malformed SfM file"), std::string::npos);
}
