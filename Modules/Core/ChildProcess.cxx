#include <vimlop/Core/ChildProcess.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace vimlop
{

namespace
{

double seconds(const timeval& t)
{
  return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
}

double nowS()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void closeOnce(int& fd)
{
  if (fd >= 0)
  {
    ::close(fd);
    fd = -1;
  }
}

/// A file descriptor closed on every path out.
struct Descriptor
{
  int fd = -1;
  Descriptor() = default;
  explicit Descriptor(int d)
    : fd(d)
  {
  }
  ~Descriptor() { closeOnce(this->fd); }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
};

/// What a child gets before its program starts: its stdout and stderr
/// (descriptors of the parent's, -1 to share the parent's own), its folder,
/// its process group and whether it dies with the thread that started it.
struct SpawnSettings
{
  int stdoutFd = -1;
  int stderrFd = -1;
  const std::string* workingDirectory = nullptr;
  bool ownProcessGroup = false;
  bool endsWithParent = false;
};

/// The program's path: searched on PATH (as execvp would) when it has no '/'.
/// Done in the parent, before the fork, because the child may only make
/// async-signal-safe calls.
std::string programPath(const std::string& program)
{
  if (program.find('/') != std::string::npos)
  {
    return program;
  }
  const char* path = std::getenv("PATH");
  std::string folders = path && *path ? path : "/usr/local/bin:/usr/bin:/bin";
  size_t begin = 0;
  while (begin <= folders.size())
  {
    const size_t end = std::min(folders.find(':', begin), folders.size());
    const std::string folder = end > begin ? folders.substr(begin, end - begin) : ".";
    const std::string candidate = folder + "/" + program;
    struct stat info
    {
    };
    if (::stat(candidate.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
      ::access(candidate.c_str(), X_OK) == 0)
    {
      return candidate;
    }
    begin = end + 1;
  }
  return std::string();
}

/// Why a child could not start: the step that failed and its errno, sent
/// to the parent through a pipe that closes when its program starts.
struct SpawnFailure
{
  int step = 0; // 1: its folder, 2: its outputs, 3: exec
  int error = 0;
};

[[noreturn]] void failInChild(int reportFd, int step)
{
  const SpawnFailure failure{ step, errno };
  [[maybe_unused]] const ssize_t written = ::write(reportFd, &failure, sizeof(failure));
  ::_exit(127);
}

/// Starts the program with its stdin /dev/null and the settings given. A
/// fork and exec rather than posix_spawn: only a forked child can ask for a
/// parent-death signal before its program starts.
pid_t spawn(const std::vector<std::string>& arguments, const SpawnSettings& settings)
{
  if (arguments.empty() || arguments.front().empty())
  {
    throw Error("child process: no program given");
  }
  const std::string path = programPath(arguments.front());
  if (path.empty())
  {
    throwFileError(
      arguments.front(), std::string("cannot start it (") + std::strerror(ENOENT) + ")");
  }
  std::vector<char*> argv;
  for (const std::string& a : arguments)
  {
    argv.push_back(const_cast<char*>(a.c_str()));
  }
  argv.push_back(nullptr);
  const Descriptor input(::open("/dev/null", O_RDONLY | O_CLOEXEC));
  int report[2] = { -1, -1 };
  if (input.fd < 0 || ::pipe2(report, O_CLOEXEC) != 0)
  {
    throwFileError(
      arguments.front(), std::string("cannot start it (") + std::strerror(errno) + ")");
  }
  const Descriptor reportRead(report[0]);
  Descriptor reportWrite(report[1]);
  const pid_t parent = ::getpid();
  const char* folder = settings.workingDirectory && !settings.workingDirectory->empty()
    ? settings.workingDirectory->c_str()
    : nullptr;
  const pid_t pid = ::fork();
  if (pid < 0)
  {
    throwFileError(
      arguments.front(), std::string("cannot start it (") + std::strerror(errno) + ")");
  }
  if (pid == 0)
  {
    // The child: async-signal-safe calls only, until exec.
    if (settings.endsWithParent)
    {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent)
      {
        ::_exit(127); // the parent ended before the request took hold
      }
    }
    if (settings.ownProcessGroup)
    {
      ::setpgid(0, 0);
    }
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    if (folder && ::chdir(folder) != 0)
    {
      failInChild(report[1], 1);
    }
    if (::dup2(input.fd, 0) < 0 || (settings.stdoutFd >= 0 && ::dup2(settings.stdoutFd, 1) < 0) ||
      (settings.stderrFd >= 0 && ::dup2(settings.stderrFd, 2) < 0))
    {
      failInChild(report[1], 2);
    }
    ::execv(path.c_str(), argv.data());
    failInChild(report[1], 3);
  }
  if (settings.ownProcessGroup)
  {
    ::setpgid(pid, pid); // also here: a kill(-pid) right away must find the group
  }
  closeOnce(reportWrite.fd);
  SpawnFailure failure;
  ssize_t got = 0;
  do
  {
    got = ::read(reportRead.fd, &failure, sizeof(failure));
  } while (got < 0 && errno == EINTR);
  if (got == static_cast<ssize_t>(sizeof(failure)))
  {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR)
    {
    }
    const std::string why = std::strerror(failure.error);
    if (failure.step == 1)
    {
      throwFileError(
        arguments.front(), "cannot start it in '" + *settings.workingDirectory + "' (" + why + ")");
    }
    throwFileError(arguments.front(), "cannot start it (" + why + ")");
  }
  return pid;
}

/// Waits for the child with wait4(), which gives its own cost. With
/// `keepRunning`, the wait polls it and stops the child (its process group)
/// when it says so: SIGTERM, then SIGKILL after `graceS`.
ChildProcessResult waitFor(pid_t pid, const std::string& program, double startS,
  const std::function<bool()>& keepRunning = nullptr, double graceS = 0.0)
{
  int status = 0;
  rusage usage{};
  pid_t waited = 0;
  bool stopped = false;
  bool killed = false;
  double stopS = 0.0;
  for (;;)
  {
    waited = ::wait4(pid, &status, keepRunning ? WNOHANG : 0, &usage);
    if (waited == pid || (waited < 0 && errno != EINTR))
    {
      break;
    }
    if (waited < 0 || !keepRunning)
    {
      continue; // EINTR
    }
    if (!stopped && !keepRunning())
    {
      stopped = true;
      stopS = nowS();
      ::kill(-pid, SIGTERM);
    }
    if (stopped && !killed && nowS() - stopS > graceS)
    {
      killed = true;
      ::kill(-pid, SIGKILL);
    }
    ::usleep(50000);
  }
  ChildProcessResult result;
  result.wallS = nowS() - startS;
  result.stopped = stopped;
  if (waited != pid)
  {
    throwFileError(program, std::string("lost the child process (") + std::strerror(errno) + ")");
  }
  if (WIFEXITED(status))
  {
    result.exitCode = WEXITSTATUS(status);
  }
  else if (WIFSIGNALED(status))
  {
    result.signal = WTERMSIG(status);
  }
  result.userCpuS = seconds(usage.ru_utime);
  result.systemCpuS = seconds(usage.ru_stime);
  // Linux gives ru_maxrss in KiB.
  result.peakResidentMiB = static_cast<double>(usage.ru_maxrss) / 1024.0;
  return result;
}

/// Opens (replacing) a file the child writes; the message names the file.
int openOutput(const std::string& path)
{
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0)
  {
    throwFileError(
      path, std::string("cannot write the child's output (") + std::strerror(errno) + ")");
  }
  return fd;
}

} // namespace

ChildProcessResult runChildProcess(const std::vector<std::string>& arguments,
  const std::string& stdoutPath, const std::string& stderrPath)
{
  ChildProcessOptions options;
  options.stdoutPath = stdoutPath;
  options.stderrPath = stderrPath;
  return runChildProcess(arguments, options);
}

ChildProcessResult runChildProcess(
  const std::vector<std::string>& arguments, const ChildProcessOptions& options)
{
  // Opened here, so that the message names the file (the child could only fail).
  const Descriptor output(options.stdoutPath.empty() ? -1 : openOutput(options.stdoutPath));
  // One file for both, as the shell's "> log 2>&1": one open file, so that
  // neither stream overwrites the other.
  const bool shared = !options.stderrPath.empty() && options.stderrPath == options.stdoutPath;
  const Descriptor errors(
    options.stderrPath.empty() || shared ? -1 : openOutput(options.stderrPath));
  SpawnSettings settings;
  settings.stdoutFd = output.fd;
  settings.stderrFd = shared ? output.fd : errors.fd;
  settings.workingDirectory = &options.workingDirectory;
  settings.ownProcessGroup = static_cast<bool>(options.keepRunning);
  settings.endsWithParent = options.endsWithParent;
  const double start = nowS();
  const pid_t pid = spawn(arguments, settings);
  return waitFor(pid, arguments.front(), start, options.keepRunning, options.stopGraceS);
}

ChildProcess::ChildProcess(const std::vector<std::string>& arguments, bool endsWithParent)
{
  // Both pipes close on exec, so that no other child started meanwhile
  // holds them open; the child's own ends are its dup2() copies.
  int output[2] = { -1, -1 };
  int errors[2] = { -1, -1 };
  if (::pipe2(output, O_CLOEXEC) != 0 || ::pipe2(errors, O_CLOEXEC) != 0)
  {
    const std::string why = std::strerror(errno);
    for (int fd : { output[0], output[1], errors[0], errors[1] })
    {
      if (fd >= 0)
      {
        ::close(fd);
      }
    }
    throw Error("child process: cannot make its pipes (" + why + ")");
  }
  // Its own process group, so that a kill reaches what it started too (a
  // shell's commands), and a terminal's Ctrl-C reaches the parent alone,
  // which ends the child as it unwinds.
  SpawnSettings settings;
  settings.stdoutFd = output[1];
  settings.stderrFd = errors[1];
  settings.ownProcessGroup = true;
  settings.endsWithParent = endsWithParent;
  this->StartS = nowS();
  try
  {
    this->Pid = spawn(arguments, settings);
  }
  catch (...)
  {
    for (int fd : { output[0], output[1], errors[0], errors[1] })
    {
      ::close(fd);
    }
    throw;
  }
  ::close(output[1]);
  ::close(errors[1]);
  this->Output = output[0];
  this->Errors = errors[0];
  this->Program = arguments.front();
}

ChildProcess::~ChildProcess()
{
  if (this->Pid > 0)
  {
    try
    {
      this->finish(true);
    }
    catch (const Error&)
    {
      // Nothing to tell from a destructor; the child is gone either way.
    }
  }
}

void ChildProcess::readErrorOutput()
{
  char buffer[4096];
  const ssize_t n = ::read(this->Errors, buffer, sizeof(buffer));
  if (n <= 0)
  {
    if (n == 0 || errno != EINTR)
    {
      closeOnce(this->Errors);
    }
    return;
  }
  this->ErrorText.append(buffer, static_cast<std::size_t>(n));
  if (this->ErrorText.size() > 4096)
  {
    this->ErrorText.erase(0, this->ErrorText.size() - 4096);
  }
}

std::size_t ChildProcess::read(char* into, std::size_t bytes, double idleTimeoutS)
{
  std::size_t got = 0;
  while (got < bytes && this->Output >= 0)
  {
    // Its stderr is read as well, so that a child blocked on a full stderr
    // pipe does not stop writing its stdout.
    pollfd fds[2] = { { this->Output, POLLIN, 0 }, { this->Errors, POLLIN, 0 } };
    const int timeoutMs = static_cast<int>(std::ceil(std::max(0.0, idleTimeoutS) * 1000.0));
    const int ready = ::poll(fds, 2, timeoutMs);
    if (ready < 0 && errno == EINTR)
    {
      continue;
    }
    if (ready == 0)
    {
      char timeout[32];
      std::snprintf(timeout, sizeof(timeout), "%g", idleTimeoutS);
      throwFileError(this->Program, std::string("sent nothing for ") + timeout + " s");
    }
    if (ready < 0)
    {
      throw Error(
        "'" + this->Program + "': cannot wait for its output (" + std::strerror(errno) + ")");
    }
    if (fds[1].revents != 0)
    {
      this->readErrorOutput();
    }
    if (fds[0].revents != 0)
    {
      const ssize_t n = ::read(this->Output, into + got, bytes - got);
      if (n < 0 && errno == EINTR)
      {
        continue;
      }
      if (n <= 0)
      {
        closeOnce(this->Output); // its end (or an error reading it: the same for a reader)
        break;
      }
      got += static_cast<std::size_t>(n);
    }
  }
  return got;
}

ChildProcessResult ChildProcess::finish(bool kill)
{
  if (this->Pid <= 0)
  {
    throwFileError(this->Program, "the child process was finished already");
  }
  closeOnce(this->Output); // a child still writing gets EPIPE and ends
  if (kill)
  {
    ::kill(-this->Pid, SIGKILL);
  }
  const double deadline = nowS() + 10.0;
  while (this->Errors >= 0)
  {
    pollfd fd = { this->Errors, POLLIN, 0 };
    const double left = deadline - nowS();
    const int ready = left > 0.0 ? ::poll(&fd, 1, static_cast<int>(left * 1000.0) + 1) : 0;
    if (ready < 0 && errno == EINTR)
    {
      continue;
    }
    if (ready <= 0)
    {
      ::kill(-this->Pid, SIGKILL); // its stderr stays open: it is stuck or forked
      closeOnce(this->Errors);
      break;
    }
    this->readErrorOutput();
  }
  const pid_t pid = this->Pid;
  this->Pid = -1;
  return waitFor(pid, this->Program, this->StartS);
}

std::string currentExecutablePath()
{
  std::vector<char> path(4096);
  const ssize_t length = ::readlink("/proc/self/exe", path.data(), path.size() - 1);
  if (length <= 0)
  {
    throw Error(std::string("cannot find the running program (/proc/self/exe: ") +
      std::strerror(errno) + ")");
  }
  return std::string(path.data(), static_cast<size_t>(length));
}

} // namespace vimlop
