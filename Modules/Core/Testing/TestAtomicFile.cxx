#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace vimlop;

namespace
{

namespace fs = std::filesystem;

std::string contentsOf(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string messageOf(const std::string& path, const std::string& contents)
{
  try
  {
    writeFileAtomically(path, contents);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(AtomicFile, WritesTheContentsAndLeavesNoTemporaryFile)
{
  const fs::path file = fixtures::freshTestFolder("atomic-write") / "result.json";
  const std::string contents = "{\n  \"a\": 1\n}\n";
  writeFileAtomically(file.string(), contents);
  EXPECT_EQ(contentsOf(file), contents);
  EXPECT_FALSE(fs::exists(file.string() + ".part"));
}

TEST(AtomicFile, ReplacesAnExistingFileWhole)
{
  const fs::path file = fixtures::freshTestFolder("atomic-replace") / "notes.txt";
  std::ofstream(file) << "an older and much longer text than the new one\n";
  writeFileAtomically(file.string(), "new\n");
  EXPECT_EQ(contentsOf(file), "new\n");
}

TEST(AtomicFile, CreatesMissingParentFolders)
{
  const fs::path file = fixtures::freshTestFolder("atomic-parents") / "a" / "b" / "c.txt";
  writeFileAtomically(file.string(), "x");
  EXPECT_EQ(contentsOf(file), "x");
}

TEST(AtomicFile, APathUnderARegularFileNamesThePath)
{
  const fs::path blocker = fixtures::freshTestFolder("atomic-blocked") / "not-a-folder";
  std::ofstream(blocker) << "a file where a folder would have to be\n";
  const std::string path = (blocker / "out.json").string();
  EXPECT_EQ(messageOf(path, "{}"), "'" + path + "': cannot write the file (Not a directory)");
  EXPECT_FALSE(fs::exists(path + ".part"));
}

TEST(AtomicFile, AFolderInTheWayGivesTheReasonAndKeepsTheFolder)
{
  const fs::path target = fixtures::freshTestFolder("atomic-folder-in-the-way") / "out.json";
  fs::create_directories(target / "inside");
  const std::string message = messageOf(target.string(), "{}");
  EXPECT_EQ(message.rfind("'" + target.string() + "': cannot write the file (", 0), 0u) << message;
  EXPECT_EQ(message.back(), ')') << message;
  EXPECT_TRUE(fs::is_directory(target / "inside"));
  EXPECT_FALSE(fs::exists(target.string() + ".part"));
}

TEST(AtomicFile, SyncToDiskNamesAPathItCannotFlush)
{
  const fs::path folder = fixtures::freshTestFolder("atomic-sync");
  fs::create_directories(folder);
  EXPECT_NO_THROW(syncToDisk(folder.string()));
  const std::string missing = (folder / "missing").string();
  EXPECT_EQ(fixtures::errorMessageOf([&] { syncToDisk(missing); }),
    "'" + missing + "': cannot flush it to disk (No such file or directory)");
}

TEST(AtomicFile, ReadsAWholeFileAndNamesOneItCannotRead)
{
  const fs::path folder = fixtures::freshTestFolder("atomic-read");
  const std::string bytes = std::string("a\0b\n", 4) + std::string(100000, 'x');
  writeFileAtomically((folder / "f.bin").string(), bytes);
  EXPECT_EQ(readWholeFile((folder / "f.bin").string()), bytes);
  writeFileAtomically((folder / "empty").string(), "");
  EXPECT_EQ(readWholeFile((folder / "empty").string()), "");
  const std::string missing = (folder / "missing").string();
  EXPECT_EQ(fixtures::errorMessageOf([&] { readWholeFile(missing); }),
    "'" + missing + "': cannot read it (No such file or directory)");
  EXPECT_EQ(fixtures::errorMessageOf([&] { readWholeFile(folder.string()); }),
    "'" + folder.string() + "': cannot read it (Is a directory)");
}
