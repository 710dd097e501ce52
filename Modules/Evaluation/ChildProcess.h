#ifndef vimlop_ChildProcess_h
#define vimlop_ChildProcess_h

#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief How a child process ended and what it cost, as its parent measured
 * it (runChildProcess()).
 */
struct ChildProcessResult
{
  /// Its exit code, or -1 when a signal ended it.
  int exitCode = -1;
  /// The signal that ended it (0 when it exited).
  int signal = 0;
  /// From its start to its end, by the parent's steady clock, s.
  double wallS = 0.0;
  /// Its user and system CPU time, every thread (wait4's rusage), s.
  double userCpuS = 0.0;
  double systemCpuS = 0.0;
  /// Its peak resident memory (rusage ru_maxrss), MiB. Linux carries it
  /// across exec: it is at least the parent's peak when it was spawned
  /// (ProcessMemory.h has the child's own, from inside it).
  double peakResidentMiB = 0.0;
};

/**
 * @brief Runs `arguments` (the program, found on PATH when it has no '/',
 * then its arguments) as a child process with posix_spawn and waits for it
 * with wait4(), which gives its own peak memory and CPU time (not the
 * parent's, nor those of its earlier siblings). Its stdout and stderr go to
 * the files `stdoutPath` and `stderrPath` (replaced; both into one file when
 * they are the same path), or to the parent's own when empty; its stdin is
 * /dev/null.
 * @throws vimlop::Error when there is no program, it cannot be started, or
 * an output file cannot be opened.
 */
ChildProcessResult runChildProcess(const std::vector<std::string>& arguments,
  const std::string& stdoutPath = std::string(), const std::string& stderrPath = std::string());

/**
 * @brief The path of the running program (/proc/self/exe), to start it again
 * as a child.
 * @throws vimlop::Error when it cannot be read.
 */
std::string currentExecutablePath();

} // namespace vimlop

#endif
