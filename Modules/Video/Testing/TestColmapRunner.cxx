// ColmapRunner's handling of COLMAP's randomised matching and mapping, with a stand-in for
// the `colmap` program whose mapper registers as many frames as a list says.

#include "ColmapBinaryWriting.h"
#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Video/ColmapBinaryModel.h>
#include <vimlop/Video/ColmapRunner.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

using namespace vimlop;
namespace fs = std::filesystem;

namespace
{

/// A binary images.bin of `count` posed images without 2-D points.
void writeImages(const fs::path& folder, std::uint32_t count)
{
  fs::create_directories(folder);
  std::ofstream f(folder / "images.bin", std::ios::binary);
  fixtures::put<std::uint64_t>(f, count);
  for (std::uint32_t id = 1; id <= count; ++id)
  {
    fixtures::putImage(f, id, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero(), 1,
      "frame" + std::to_string(id) + ".png", {});
  }
}

/// A folder with 12 frames and a stand-in `colmap` whose n-th mapper run
/// registers `registered[n]` frames (0: no model); it logs each step, with
/// its random seed, in `calls`. Returns the folder.
fs::path fakeColmap(const std::string& name, const std::vector<int>& registered)
{
  const fs::path root = fs::path(VIMLOP_TEST_OUTPUT_DIR) / name;
  fs::remove_all(root);
  fs::create_directories(root / "frames");
  for (int f = 0; f < 12; ++f)
  {
    std::ofstream(root / "frames" / ("frame" + std::to_string(f) + ".png")) << "not read";
  }
  std::ofstream runs(root / "runs");
  for (int n : registered)
  {
    runs << n << "\n";
    if (n > 0)
    {
      writeImages(root / "models" / std::to_string(n), static_cast<std::uint32_t>(n));
    }
  }
  const fs::path script = root / "colmap";
  std::ofstream(script) << "#!/bin/sh\n"
                        << "D='" << root.string() << "'\n"
                        << "step=$1; shift; seed=\n"
                        << "while [ $# -gt 0 ]; do\n"
                        << "  [ \"$1\" = --output_path ] && out=$2\n"
                        << "  [ \"$1\" = --random_seed ] && seed=\" $2\"\n"
                        << "  shift\n"
                        << "done\n"
                        << "echo \"$step$seed\" >> \"$D/calls\"\n"
                        << "[ \"$step\" = mapper ] || exit 0\n"
                        << "k=$(grep -c ^mapper \"$D/calls\")\n"
                        << "n=$(sed -n \"${k}p\" \"$D/runs\")\n"
                        << "[ \"$n\" = 0 ] && exit 0\n"
                        << "mkdir -p \"$out/0\" && cp \"$D/models/$n/images.bin\" \"$out/0/\"\n";
  fs::permissions(script, fs::perms::owner_all, fs::perm_options::add);
  return root;
}

std::string run(const fs::path& root, int mapperRuns = 3)
{
  ColmapRunnerOptions options;
  options.executable = (root / "colmap").string();
  options.mapperRuns = mapperRuns;
  return ColmapRunner(options).run(
    (root / "frames").string(), PinholeCamera(), (root / "work").string());
}

/// Images registered in the model folder `model`, read as the runner reads them.
size_t imagesIn(const std::string& model)
{
  detail::ColmapModel read;
  detail::readImagesBinary((fs::path(model) / "images.bin").string(), read);
  return read.images.size();
}

} // namespace

TEST(ColmapRunner, MatchesAndMapsAgainWhileTheMapperRegistersFewerThanHalfTheFrames)
{
  const fs::path root = fakeColmap("colmap-runner-again", { 3, 12, 12 });
  const std::string model = run(root);
  EXPECT_EQ(imagesIn(model), 12u);
  EXPECT_EQ(readWholeFile((root / "calls").string()),
    "help\nfeature_extractor\nexhaustive_matcher 1\nmapper 1\ndatabase_cleaner\nexhaustive_matcher "
    "2\n"
    "mapper 2\nmodel_converter\n");
  EXPECT_NE(readWholeFile((root / "work" / "colmap.log").string())
              .find("vimlop: mapper run 1 of 3 registered 3 of 12 frames\n"),
    std::string::npos);
  EXPECT_FALSE(fs::exists(root / "work" / "sparse-best"));
}

TEST(ColmapRunner, KeepsTheMapperRunThatRegisteredMostWhenNoneReachesHalf)
{
  const fs::path root = fakeColmap("colmap-runner-most", { 4, 0, 2 });
  EXPECT_EQ(imagesIn(run(root)), 4u);
  const std::string log = readWholeFile((root / "work" / "colmap.log").string());
  EXPECT_NE(log.find("mapper run 2 of 3 registered 0 of 12 frames"), std::string::npos) << log;
  EXPECT_NE(log.find("mapper run 3 of 3 registered 2 of 12 frames"), std::string::npos) << log;
}

TEST(ColmapRunner, SaysWhenNoMapperRunGaveAModel)
{
  const fs::path root = fakeColmap("colmap-runner-none", { 0, 0 });
  try
  {
    run(root, 2);
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_EQ(std::string(e.what()),
      "COLMAP: the mapper reconstructed no model (see '" + (root / "work" / "colmap.log").string() +
        "')");
  }
}

TEST(ColmapRunner, RefusesFewerThanOneMapperRun)
{
  const fs::path root = fakeColmap("colmap-runner-zero", {});
  try
  {
    run(root, 0);
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "COLMAP: the mapper must run at least once, got 0 runs");
  }
  EXPECT_FALSE(fs::exists(root / "calls"));
}
