#ifndef vimlop_TestFolders_h
#define vimlop_TestFolders_h

// Folders that tests write into, under the build's Testing/Temporary, and
// the files in them read back.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace vimlop::fixtures
{

/**
 * @brief An empty folder `name` under the tests' output folder (removed and
 * made again).
 *
 * ctest runs each test of a binary in its own process, two at a time in CI,
 * so two tests must never share a folder: with `perTest` (the default) the
 * running test's name is appended to `name`.
 */
inline std::filesystem::path freshTestFolder(const std::string& name, bool perTest = true)
{
  std::string leaf = name;
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  if (perTest && test != nullptr)
  {
    leaf += std::string("-") + test->test_suite_name() + "." + test->name();
  }
  const std::filesystem::path dir = std::filesystem::path(VIMLOP_TEST_OUTPUT_DIR) / leaf;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// @brief The whole of a file, its bytes as they are ("" when it cannot be read).
inline std::string fileBytes(const std::filesystem::path& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

} // namespace vimlop::fixtures

#endif
