#ifndef vimlop_ChildProcess_h
#define vimlop_ChildProcess_h

#include <cstddef>
#include <functional>
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
  /// True when it ended because ChildProcessOptions::keepRunning asked it to stop.
  bool stopped = false;
};

/**
 * @brief How runChildProcess() starts a child and watches it; the defaults
 * are a child that shares the parent's folder, outputs and process group.
 */
struct ChildProcessOptions
{
  /// Files its stdout and stderr go to (replaced; both into one file when
  /// they are the same path); empty: the parent's own.
  std::string stdoutPath;
  std::string stderrPath;
  /// The folder it starts in (relative paths among its arguments are read
  /// from there); empty: the parent's.
  std::string workingDirectory;
  /// Killed (SIGKILL) when the thread that started it ends, e.g. when the
  /// parent is killed outright: a batch runner killed with kill -9 leaves no
  /// child working on unseen (Linux's parent-death signal). The thread that
  /// calls runChildProcess() waits for the child, so it outlives it otherwise.
  bool endsWithParent = false;
  /// Asked about every 50 ms while the child runs; when it returns false the
  /// child's process group gets SIGTERM (a VIMLOP command then stops cleanly,
  /// as on Ctrl-C), and SIGKILL `stopGraceS` seconds later. With it set the
  /// child runs in a process group of its own, so that the stop reaches what
  /// it started too, and a terminal's Ctrl-C reaches the parent alone.
  std::function<bool()> keepRunning;
  /// Seconds between the SIGTERM and the SIGKILL of a stop.
  double stopGraceS = 10.0;
};

/**
 * @brief Runs `arguments` (the program, found on PATH when it has no '/',
 * then its arguments) as a child process and waits for it with wait4(), which gives its own peak
 * memory and CPU time (not the parent's, nor those of its earlier siblings). Its stdout and stderr
 * go to the files `stdoutPath` and `stderrPath` (replaced; both into one file when they are the
 * same path), or to the parent's own when empty; its stdin is /dev/null.
 * @throws vimlop::Error when there is no program, it cannot be started, or
 * an output file cannot be opened.
 */
ChildProcessResult runChildProcess(const std::vector<std::string>& arguments,
  const std::string& stdoutPath = std::string(), const std::string& stderrPath = std::string());

/**
 * @brief runChildProcess() with every setting of `options`: its folder,
 * outputs, whether it ends with its parent and when to stop it.
 * @throws vimlop::Error as runChildProcess(), and "cannot start it in
 * 'folder'" when its working directory cannot be entered.
 */
ChildProcessResult runChildProcess(
  const std::vector<std::string>& arguments, const ChildProcessOptions& options);

/**
 * @brief A child process whose output the parent reads as it comes (a
 * decoder's frames, say), with a deadline on every wait: its stdout is a
 * pipe read with read(), its stderr a pipe kept (its last 4 KiB) for the
 * message when it fails, its stdin /dev/null. It runs in a process group of
 * its own, killed as a whole; a child still running when the object goes is
 * killed and reaped.
 */
class ChildProcess
{
public:
  /**
   * @brief Starts `arguments` as runChildProcess() does; with
   * `endsWithParent`, it is killed when the thread that started it ends
   * (ChildProcessOptions::endsWithParent).
   * @throws vimlop::Error when there is no program or it cannot be started.
   */
  explicit ChildProcess(const std::vector<std::string>& arguments, bool endsWithParent = false);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /**
   * @brief Reads `bytes` bytes of its stdout into `into`; returns how many
   * came, fewer only when its stdout ended first.
   * @throws vimlop::Error "'program': sent nothing for S s" when no byte came
   * for `idleTimeoutS` seconds (the child is left running: finish() kills it).
   */
  std::size_t read(char* into, std::size_t bytes, double idleTimeoutS);

  /// @brief The last 4 KiB it wrote to stderr so far (all of it after finish()).
  const std::string& errorOutput() const { return this->ErrorText; }

  /**
   * @brief Closes its stdout, kills it first when `kill` (a reader that has
   * what it wanted), waits for it to end and says how it ended. Its stderr
   * is read to its end, 10 s at most; then it is killed.
   */
  ChildProcessResult finish(bool kill);

private:
  void readErrorOutput();

  std::string Program;
  int Pid = -1;
  int Output = -1; ///< read end of its stdout
  int Errors = -1; ///< read end of its stderr
  std::string ErrorText;
  double StartS = 0.0;
};

/**
 * @brief The path of the running program (/proc/self/exe), to start it again
 * as a child.
 * @throws vimlop::Error when it cannot be read.
 */
std::string currentExecutablePath();

} // namespace vimlop

#endif
