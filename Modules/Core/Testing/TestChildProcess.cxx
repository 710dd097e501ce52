#include <vimlop/Core/ChildProcess.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include <sys/resource.h>

namespace vimlop
{
namespace
{

namespace fs = std::filesystem;

TEST(ChildProcess, RunsAProgramWithItsOutputsInFilesAndItsOwnCost)
{
  const fs::path dir = fixtures::freshTestFolder("child-process");
  // About 0.2 s of CPU in the child (a shell loop), nothing in the parent.
  const ChildProcessResult r = runChildProcess(
    { "/bin/sh", "-c",
      "echo out; echo err >&2; i=0; while [ $i -lt 200000 ]; do i=$((i+1)); done; exit 7" },
    (dir / "out.txt").string(), (dir / "err.txt").string());
  EXPECT_EQ(r.exitCode, 7);
  EXPECT_EQ(r.signal, 0);
  EXPECT_EQ(fixtures::fileBytes(dir / "out.txt"), "out\n");
  EXPECT_EQ(fixtures::fileBytes(dir / "err.txt"), "err\n");
  EXPECT_GT(r.userCpuS + r.systemCpuS, 0.0);
  EXPECT_GE(r.wallS, 0.8 * (r.userCpuS + r.systemCpuS));
  // A shell's peak, bounded by this process's (Linux counts the parent's
  // memory at the spawn as the child's): not a sum of the two.
  rusage self{};
  getrusage(RUSAGE_SELF, &self);
  EXPECT_GT(r.peakResidentMiB, 0.0);
  EXPECT_LT(r.peakResidentMiB, self.ru_maxrss / 1024.0 + 32.0);
}

TEST(ChildProcess, SaysWhenAProgramEndsByASignal)
{
  const ChildProcessResult r = runChildProcess({ "/bin/sh", "-c", "kill -TERM $$" });
  EXPECT_EQ(r.exitCode, -1);
  EXPECT_EQ(r.signal, 15);
}

TEST(ChildProcess, RefusesAMissingProgramOrAnUnwritableOutput)
{
  EXPECT_EQ(
    fixtures::errorMessageOf([] { runChildProcess({}); }), "child process: no program given");
  EXPECT_EQ(fixtures::errorMessageOf([] { runChildProcess({ "/no/such/program" }); }),
    "'/no/such/program': cannot start it (No such file or directory)");
  EXPECT_EQ(
    fixtures::errorMessageOf([] { runChildProcess({ "/bin/true" }, "/no/such/folder/out.txt"); }),
    "'/no/such/folder/out.txt': cannot write the child's output (No such file or directory)");
}

TEST(ChildProcess, FindsTheRunningProgram)
{
  EXPECT_TRUE(fs::exists(currentExecutablePath()));
  EXPECT_NE(currentExecutablePath().find("VIMLOPCoreTests"), std::string::npos);
}

TEST(ChildProcess, ReadsAChildsOutputAsItComesAndKeepsWhatItSaidOnStderr)
{
  ChildProcess child(
    { "/bin/sh", "-c", "printf abc; echo oops >&2; sleep 0.1; printf def; exit 3" });
  std::string text(8, '\0');
  EXPECT_EQ(child.read(text.data(), 6, 10.0), 6u);
  EXPECT_EQ(text.substr(0, 6), "abcdef");
  EXPECT_EQ(child.read(text.data(), 8, 10.0), 0u); // its end
  const ChildProcessResult r = child.finish(false);
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_EQ(child.errorOutput(), "oops\n");
  EXPECT_EQ(fixtures::errorMessageOf([&] { child.finish(false); }),
    "'/bin/sh': the child process was finished already");
}

TEST(ChildProcess, AChildThatFillsItsStderrStillDeliversItsOutput)
{
  // 1 MB on stderr first: a parent reading only stdout would wait forever
  // on a child blocked writing a full stderr pipe.
  ChildProcess child({ "/bin/sh", "-c", "head -c 1000000 /dev/zero | tr '\\0' e >&2; printf x" });
  char x = 0;
  EXPECT_EQ(child.read(&x, 1, 30.0), 1u);
  EXPECT_EQ(x, 'x');
  EXPECT_EQ(child.finish(false).exitCode, 0);
  EXPECT_EQ(child.errorOutput(), std::string(4096, 'e')); // the last 4 KiB
}

TEST(ChildProcess, GivesUpOnAChildThatSendsNothingAndKillsIt)
{
  ChildProcess child({ "/bin/sh", "-c", "sleep 30" });
  char byte = 0;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(fixtures::errorMessageOf([&] { child.read(&byte, 1, 0.2); }),
    "'/bin/sh': sent nothing for 0.2 s");
  const ChildProcessResult r = child.finish(true);
  EXPECT_EQ(r.signal, 9);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(ChildProcess, AChildStillRunningIsKilledWhenItsObjectGoes)
{
  const auto start = std::chrono::steady_clock::now();
  {
    // A shell waiting on a command of its own: both hold its stderr open.
    ChildProcess child({ "/bin/sh", "-c", "sleep 30 & echo started; wait" });
    std::string line(8, '\0');
    ASSERT_EQ(child.read(line.data(), 8, 10.0), 8u);
    EXPECT_EQ(line, "started\n");
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_EQ(fixtures::errorMessageOf([] { ChildProcess({ "/no/such/decoder" }); }),
    "'/no/such/decoder': cannot start it (No such file or directory)");
  EXPECT_EQ(fixtures::errorMessageOf([] { ChildProcess({}); }), "child process: no program given");
}

} // namespace
} // namespace vimlop
