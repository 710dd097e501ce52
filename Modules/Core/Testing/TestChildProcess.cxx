#include <vimlop/Core/ChildProcess.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

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

TEST(ChildProcess, StartsAChildInTheFolderItIsGiven)
{
  const fs::path dir = fixtures::freshTestFolder("child-process-folder");
  ChildProcessOptions options;
  options.workingDirectory = dir.string();
  options.stdoutPath = (dir / "pwd.txt").string();
  EXPECT_EQ(runChildProcess({ "sh", "-c", "pwd -P" }, options).exitCode, 0);
  EXPECT_EQ(fixtures::fileBytes(dir / "pwd.txt"), fs::canonical(dir).string() + "\n");
  options.workingDirectory = (dir / "no-such-folder").string();
  EXPECT_EQ(fixtures::errorMessageOf([&] { runChildProcess({ "/bin/true" }, options); }),
    "'/bin/true': cannot start it in '" + options.workingDirectory +
      "' (No such file or directory)");
  EXPECT_EQ(fixtures::errorMessageOf([] { runChildProcess({ "no-such-program-on-path" }); }),
    "'no-such-program-on-path': cannot start it (No such file or directory)");
}

TEST(ChildProcess, StopsAChildWhenAskedWithTermThenKill)
{
  // Each child says when its trap is set (a file), and is asked to stop from then on.
  const fs::path ready = fixtures::freshTestFolder("child-process-stop") / "ready";
  const std::string touch = "touch '" + ready.string() + "'; ";
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&]
  { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  ChildProcessOptions options;
  options.keepRunning = [&] { return !fs::exists(ready); };
  // A child that ends on SIGTERM, and what it started ends with it (its process group).
  const ChildProcessResult polite = runChildProcess(
    { "/bin/sh", "-c", "trap 'exit 5' TERM; " + touch + "sleep 30 & wait" }, options);
  EXPECT_TRUE(polite.stopped);
  EXPECT_EQ(polite.exitCode, 5);
  EXPECT_LT(elapsed(), 5.0);
  // A child that ignores SIGTERM gets SIGKILL after the grace period.
  fs::remove(ready);
  options.stopGraceS = 0.3;
  const ChildProcessResult stubborn = runChildProcess(
    { "/bin/sh", "-c", "trap '' TERM; " + touch + "while :; do sleep 1; done" }, options);
  EXPECT_TRUE(stubborn.stopped);
  EXPECT_EQ(stubborn.signal, SIGKILL);
  EXPECT_LT(elapsed(), 8.0);
  // Left alone, it runs to its end.
  options.keepRunning = [] { return true; };
  const ChildProcessResult untouched = runChildProcess({ "/bin/sh", "-c", "exit 4" }, options);
  EXPECT_FALSE(untouched.stopped);
  EXPECT_EQ(untouched.exitCode, 4);
}

/// Whether process `pid` is gone (or a zombie nobody reaped: it ran no more).
bool processEnded(pid_t pid)
{
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line))
  {
    return true;
  }
  const size_t paren = line.rfind(')');
  return paren != std::string::npos && line.size() > paren + 2 && line[paren + 2] == 'Z';
}

TEST(ChildProcess, AChildThatEndsWithItsParentDiesWhenTheParentIsKilled)
{
  const fs::path dir = fixtures::freshTestFolder("child-process-orphan");
  const fs::path pidFile = dir / "child.pid";
  // A parent of our own (forked) starts the child and is then killed with SIGKILL.
  const pid_t parent = ::fork();
  ASSERT_GE(parent, 0);
  if (parent == 0)
  {
    ChildProcessOptions options;
    options.endsWithParent = true;
    runChildProcess({ "/bin/sh", "-c",
                      "echo $$ > '" + pidFile.string() + ".tmp'; mv '" + pidFile.string() +
                        ".tmp' '" + pidFile.string() + "'; exec sleep 30" },
      options);
    ::_exit(0);
  }
  pid_t child = 0;
  for (int i = 0; i < 200 && child == 0; ++i)
  {
    std::ifstream in(pidFile);
    in >> child;
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  ASSERT_GT(child, 0) << "the child did not start";
  EXPECT_FALSE(processEnded(child));
  ::kill(parent, SIGKILL);
  int status = 0;
  ::waitpid(parent, &status, 0);
  bool ended = false;
  for (int i = 0; i < 200 && !ended; ++i)
  {
    ended = processEnded(child);
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  EXPECT_TRUE(ended) << "the child " << child << " outlived its killed parent";
  if (!ended)
  {
    ::kill(child, SIGKILL);
  }
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
