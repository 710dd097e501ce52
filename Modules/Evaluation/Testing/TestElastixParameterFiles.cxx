#include <vimlop/Evaluation/Peers/ElastixParameterFiles.h>

#include <gtest/gtest.h>

#include <filesystem>

using namespace vimlop;

TEST(ElastixParameterFiles, AreTheSourceTreesWhenRunFromTheBuildTree)
{
  // The tests run from the build tree: the source tree's Data/elastix.
  const std::filesystem::path folder = defaultElastixParametersFolder();
  EXPECT_TRUE(std::filesystem::is_regular_file(folder / "affine.txt")) << folder;
  EXPECT_TRUE(std::filesystem::is_regular_file(folder / "bspline.txt")) << folder;
  EXPECT_TRUE(std::filesystem::equivalent(folder, VIMLOP_SOURCE_ELASTIX_DIR)) << folder;
}
