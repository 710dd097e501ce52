#include <vimlop/Core/Error.h>
#include <vimlop/Results/InputIdentity.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace vimlop;
namespace fs = std::filesystem;

TEST(InputIdentity, AFileIsItsSizeAndTheSha256OfItsBytes)
{
  const fs::path file = fixtures::freshTestFolder("identity-file") / "k.yaml";
  std::ofstream(file, std::ios::binary) << "abc";
  const RegistrationRecord::InputFile input = identifyInput("intrinsics", file.string());
  EXPECT_EQ(input.role, "intrinsics");
  EXPECT_EQ(input.path, file.string());
  EXPECT_EQ(input.bytes, 3u);
  EXPECT_EQ(input.sha256, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(InputIdentity, AFolderIsItsFilesWhereverItLiesAndAnyChangeShows)
{
  const fs::path root = fixtures::freshTestFolder("identity-folder");
  for (const fs::path& folder : { root / "a", root / "b" })
  {
    fs::create_directories(folder / "sub");
    std::ofstream(folder / "frame001.png") << "one";
    std::ofstream(folder / "sub" / "frame002.png") << "two";
  }
  const auto a = identifyInput("frames", (root / "a").string());
  const auto b = identifyInput("frames", (root / "b").string());
  EXPECT_EQ(a.bytes, 6u);
  EXPECT_EQ(a.sha256, b.sha256);
  // A renamed file, or one byte changed, is another input.
  fs::rename(root / "b" / "frame001.png", root / "b" / "frame003.png");
  EXPECT_NE(identifyInput("frames", (root / "b").string()).sha256, a.sha256);
  std::ofstream(root / "a" / "frame001.png") << "One";
  EXPECT_NE(identifyInput("frames", (root / "a").string()).sha256, a.sha256);
  EXPECT_EQ(fixtures::errorMessageOf([&] { identifyInput("ct", (root / "missing").string()); }),
    "'" + (root / "missing").string() + "': no such file or folder to identify");
}

TEST(InputIdentity, AnInputThatCannotBeIdentifiedIsListedWithoutDigestAndWhy)
{
  const fs::path root = fixtures::freshTestFolder("identity-list");
  std::ofstream(root / "k.yaml") << "abc";
  std::vector<std::string> problems;
  const auto inputs = identifyInputs({ { "intrinsics", (root / "k.yaml").string() }, { "mesh", "" },
                                       { "tracker", (root / "gone.csv").string() } },
    problems);
  ASSERT_EQ(inputs.size(), 2u); // the empty path is no input
  EXPECT_EQ(inputs[0].bytes, 3u);
  EXPECT_EQ(inputs[1].role, "tracker");
  EXPECT_TRUE(inputs[1].sha256.empty());
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0],
    "cannot identify the tracker input: '" + (root / "gone.csv").string() +
      "': no such file or folder to identify");
}
