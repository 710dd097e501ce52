// COLMAP import against models written by the real `colmap` program (built
// only when CMake found it; CI installs Debian's package).

#include "RenderedSequence.h"
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/SimilarityEstimation.h>
#include <vimlop/Video/ColmapImport.h>
#include <vimlop/Video/ColmapRunner.h>

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>

using namespace vimlop;
namespace fs = std::filesystem;

namespace
{

/// COLMAP's reconstruction of the rendered sequence; returns its work folder.
std::string runColmap()
{
  const fixtures::Sequence& s = fixtures::sequence();
  const std::string root = std::string(VIMLOP_TEST_OUTPUT_DIR) + "/colmap-real";
  const std::string images = root + "/images";
  fs::remove_all(root);
  fs::create_directories(images);
  for (size_t f = 0; f < s.frames.size(); ++f)
  {
    cv::imwrite(images + "/" + s.names[f], s.frames[f]);
  }
  ColmapRunnerOptions options;
  options.executable = VIMLOP_COLMAP_EXECUTABLE;
  ColmapRunner(options).run(images, s.intrinsics, root + "/work");
  return root + "/work";
}

} // namespace

// One test, so that COLMAP runs once (ctest runs each test in its own process).
TEST(ColmapReal, ImportsTheModelsOfTheRealProgram)
{
  const fixtures::Sequence& s = fixtures::sequence();
  const std::string work = runColmap();
  const SfmReconstruction binary =
    readColmapModel(work + "/sparse/0", ColmapFormat::Binary, s.names);
  const SfmReconstruction text =
    readColmapModel(ColmapRunner::textModelFolder(work), ColmapFormat::Text, s.names);
  ASSERT_EQ(binary.frames.size(), s.frames.size());
  EXPECT_GE(binary.numberOfRegisteredFrames(), static_cast<int>(s.frames.size()) - 2);
  EXPECT_GT(binary.points.size(), 100u);
  ASSERT_EQ(text.points.size(), binary.points.size());
  EXPECT_EQ(text.numberOfRegisteredFrames(), binary.numberOfRegisteredFrames());
  for (size_t f = 0; f < binary.frames.size(); ++f)
  {
    EXPECT_EQ(text.frames[f].registered, binary.frames[f].registered);
    // Text holds about 15 significant digits; COLMAP writes what it holds.
    EXPECT_LT(
      (text.frames[f].cameraToSfm.centre - binary.frames[f].cameraToSfm.centre).norm(), 1e-6);
    EXPECT_EQ(text.frames[f].intrinsics.cx, binary.frames[f].intrinsics.cx);
  }
  for (size_t i = 0; i < binary.points.size(); ++i)
  {
    EXPECT_LT((text.points[i].position - binary.points[i].position).norm(), 1e-6);
    ASSERT_EQ(text.points[i].observations.size(), binary.points[i].observations.size());
  }
  // The intrinsics given to COLMAP come back in VIMLOP's pixel convention.
  for (const SfmReconstruction::Frame& f : binary.frames)
  {
    if (f.registered)
    {
      EXPECT_NEAR(f.intrinsics.cx, s.intrinsics.cx, 1e-9);
      EXPECT_NEAR(f.intrinsics.cy, s.intrinsics.cy, 1e-9);
      EXPECT_NEAR(f.intrinsics.fx, s.intrinsics.fx, 1e-9);
    }
  }

  // Poses and observations read with the right conventions reproject well
  // and match the simulation up to a similarity.
  const SfmReconstruction& r = binary;
  EXPECT_LT(r.rmsReprojectionErrorPx(), 1.5);
  std::vector<Eigen::Vector3d> estimated;
  std::vector<Eigen::Vector3d> truth;
  std::vector<int> frames;
  for (size_t f = 0; f < r.frames.size(); ++f)
  {
    if (r.frames[f].registered)
    {
      estimated.push_back(r.frames[f].cameraToSfm.centre);
      truth.push_back(s.poses[f].centre);
      frames.push_back(static_cast<int>(f));
    }
  }
  const SimilarityTransform t = estimateSimilarity(estimated, truth);
  for (size_t j = 0; j < frames.size(); ++j)
  {
    EXPECT_LT((t.apply(estimated[j]) - truth[j]).norm(), 0.1) << frames[j];
    const CameraPose moved = t.apply(r.frames[frames[j]].cameraToSfm);
    // A wrong quaternion or axis convention would be off by far more.
    EXPECT_LT(rotationAngleBetween(moved.rotation, s.poses[frames[j]].rotation) * 180.0 / M_PI, 1.0)
      << frames[j];
  }
}
