#include <vimlop/Core/Error.h>
#include <vimlop/Results/ResultFolderTransaction.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

using namespace vimlop;
namespace fs = std::filesystem;

namespace
{

using Existing = ResultFolderTransaction::Existing;

std::string contentsOf(const fs::path& file)
{
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void write(const fs::path& file, const std::string& text)
{
  std::ofstream(file) << text;
}

std::string refusal(const std::string& folder, Existing existing)
{
  return fixtures::errorMessageOf([&] { ResultFolderTransaction transaction(folder, existing); });
}

/// An earlier run's complete result: result.json and a video.
fs::path oldResult(const fs::path& root)
{
  const fs::path folder = root / "out";
  fs::create_directories(folder);
  write(folder / "result.json", "old");
  write(folder / "registered.avi", "old video");
  return folder;
}

} // namespace

TEST(ResultFolderTransaction, TheFolderAppearsOnlyWhenCommittedAndWhole)
{
  const fs::path folder = fixtures::freshTestFolder("transaction-new") / "out";
  ResultFolderTransaction transaction(folder.string(), Existing::Refuse);
  EXPECT_EQ(transaction.stagingFolder(), folder.string() + ".partial");
  write(fs::path(transaction.stagingFolder()) / "result.json", "new");
  fs::create_directories(fs::path(transaction.stagingFolder()) / "frames");
  write(fs::path(transaction.stagingFolder()) / "frames" / "frame-0000.png", "png");
  EXPECT_FALSE(fs::exists(folder));
  EXPECT_TRUE(fs::exists(folder.string() + ".lock"));
  transaction.commit();
  EXPECT_EQ(contentsOf(folder / "result.json"), "new");
  EXPECT_EQ(contentsOf(folder / "frames" / "frame-0000.png"), "png");
  EXPECT_FALSE(fs::exists(folder.string() + ".partial"));
}

TEST(ResultFolderTransaction, ReplacingSwapsTheWholeFolderAndKeepsNoOldFile)
{
  const fs::path folder = oldResult(fixtures::freshTestFolder("transaction-replace"));
  {
    ResultFolderTransaction transaction(folder.string() + "/", Existing::Replace);
    EXPECT_EQ(transaction.folder(), folder.string());
    write(fs::path(transaction.stagingFolder()) / "result.json", "new");
    EXPECT_EQ(contentsOf(folder / "result.json"), "old"); // untouched until the commit
    transaction.commit();
  }
  EXPECT_EQ(contentsOf(folder / "result.json"), "new");
  EXPECT_FALSE(fs::exists(folder / "registered.avi")); // --force kept it beside the new result
  EXPECT_FALSE(fs::exists(folder.string() + ".partial"));
  EXPECT_FALSE(fs::exists(folder.string() + ".lock"));
}

TEST(ResultFolderTransaction, AnUnfinishedTransactionLeavesTheOldFolderAndNoStaging)
{
  const fs::path folder = oldResult(fixtures::freshTestFolder("transaction-abort"));
  {
    ResultFolderTransaction transaction(folder.string(), Existing::Replace);
    write(fs::path(transaction.stagingFolder()) / "result.json", "half");
  } // an error or Ctrl-C: no commit
  EXPECT_EQ(contentsOf(folder / "result.json"), "old");
  EXPECT_TRUE(fs::exists(folder / "registered.avi"));
  EXPECT_FALSE(fs::exists(folder.string() + ".partial"));
  {
    ResultFolderTransaction transaction(folder.string(), Existing::Replace);
    write(fs::path(transaction.stagingFolder()) / "registered-poses.json", "poses");
    transaction.keepStaging(); // an output failed after the poses were written
  }
  EXPECT_EQ(contentsOf(folder.string() + ".partial/registered-poses.json"), "poses");
  EXPECT_EQ(contentsOf(folder / "result.json"), "old");
}

TEST(ResultFolderTransaction, ASecondWriterIsRefusedAtOnceNamingTheFirst)
{
  const fs::path folder = fixtures::freshTestFolder("transaction-lock") / "out";
  {
    ResultFolderTransaction first(folder.string(), Existing::Refuse);
    EXPECT_EQ(refusal(folder.string(), Existing::Replace),
      "'" + folder.string() + "': another run (process " + std::to_string(::getpid()) +
        ") is writing this result folder; wait for it to end or choose another --out");
    // Another process is refused too (flock belongs to the open file, not the process).
    const pid_t child = ::fork();
    if (child == 0)
    {
      ::_exit(refusal(folder.string(), Existing::Replace).find("another run") != std::string::npos
          ? 0
          : 1);
    }
    int status = -1;
    ::waitpid(child, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  // The lock ends with its transaction.
  EXPECT_EQ(refusal(folder.string(), Existing::Refuse), "no error");
}

TEST(ResultFolderTransaction, AKilledRunLeavesNoResultAndItsStagingIsRemovedByTheNext)
{
  const fs::path folder = fixtures::freshTestFolder("transaction-killed") / "out";
  const pid_t child = ::fork();
  if (child == 0)
  {
    ResultFolderTransaction transaction(folder.string(), Existing::Refuse);
    write(fs::path(transaction.stagingFolder()) / "registered-poses.json", "poses");
    ::_exit(0); // like kill -9: no destructor runs
  }
  int status = -1;
  ::waitpid(child, &status, 0);
  EXPECT_FALSE(fs::exists(folder));
  EXPECT_TRUE(fs::exists(folder.string() + ".partial/registered-poses.json"));
  std::string note;
  ResultFolderTransaction next(folder.string(), Existing::Refuse, &note);
  EXPECT_EQ(note,
    "removed '" + folder.string() + ".partial', left by a run into '" + folder.string() +
      "' that did not finish");
  EXPECT_TRUE(fs::is_empty(next.stagingFolder()));
}

TEST(ResultFolderTransaction, ExistingFoldersAndBadNamesAreRefusedWithTheReason)
{
  const fs::path root = fixtures::freshTestFolder("transaction-refused");
  const fs::path folder = oldResult(root);
  EXPECT_EQ(refusal(folder.string(), Existing::Refuse),
    "'" + folder.string() + "': exists; choose another --out or add --force to replace it");
  // --force on a folder that holds something else: a mistyped --out.
  const fs::path home = root / "home";
  fs::create_directories(home);
  write(home / "thesis.tex", "years of work");
  EXPECT_EQ(refusal(home.string(), Existing::Replace),
    "'" + home.string() +
      "': exists and is not a VIMLOP result folder (no result.json, registered-poses.json or "
      "vimlop-export.json); "
      "refusing to replace it");
  EXPECT_EQ(contentsOf(home / "thesis.tex"), "years of work");
  write(root / "file", "x");
  EXPECT_EQ(refusal((root / "file").string(), Existing::Replace),
    "'" + (root / "file").string() + "': exists and is not a folder; choose another --out");
  EXPECT_EQ(refusal(".", Existing::Replace),
    "'.': name a folder of its own for the result (it is written beside, then renamed)");
  fs::create_directories(root / "empty");
  EXPECT_EQ(refusal((root / "empty").string(), Existing::Replace), "no error");
}
