#include <vimlop/Core/ChildProcess.h>

#include <vimlop/Core/Error.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

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

/// posix_spawn's file actions, destroyed on every path out.
struct FileActions
{
  posix_spawn_file_actions_t actions;
  FileActions() { posix_spawn_file_actions_init(&this->actions); }
  ~FileActions() { posix_spawn_file_actions_destroy(&this->actions); }
  FileActions(const FileActions&) = delete;
  FileActions& operator=(const FileActions&) = delete;
};

/// Starts the program (searched on PATH when its name has no '/') with its
/// stdin /dev/null and the file actions given.
pid_t spawn(const std::vector<std::string>& arguments, FileActions& files,
  const posix_spawnattr_t* attributes = nullptr)
{
  if (arguments.empty() || arguments.front().empty())
  {
    throw Error("child process: no program given");
  }
  posix_spawn_file_actions_addopen(&files.actions, 0, "/dev/null", O_RDONLY, 0);
  std::vector<char*> argv;
  for (const std::string& a : arguments)
  {
    argv.push_back(const_cast<char*>(a.c_str()));
  }
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = arguments.front().find('/') == std::string::npos
    ? posix_spawnp(&pid, argv[0], &files.actions, attributes, argv.data(), environ)
    : posix_spawn(&pid, argv[0], &files.actions, attributes, argv.data(), environ);
  if (spawned != 0)
  {
    throw Error("'" + arguments.front() + "': cannot start it (" + std::strerror(spawned) + ")");
  }
  return pid;
}

/// Waits for the child with wait4(), which gives its own cost.
ChildProcessResult waitFor(pid_t pid, const std::string& program, double startS)
{
  int status = 0;
  rusage usage{};
  pid_t waited = 0;
  do
  {
    waited = ::wait4(pid, &status, 0, &usage);
  } while (waited < 0 && errno == EINTR);
  ChildProcessResult result;
  result.wallS = nowS() - startS;
  if (waited != pid)
  {
    throw Error("'" + program + "': lost the child process (" + std::strerror(errno) + ")");
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

void closeOnce(int& fd)
{
  if (fd >= 0)
  {
    ::close(fd);
    fd = -1;
  }
}

} // namespace

ChildProcessResult runChildProcess(const std::vector<std::string>& arguments,
  const std::string& stdoutPath, const std::string& stderrPath)
{
  // Checked here, so that the message names the file (the child could only fail).
  for (const std::string* path : { &stdoutPath, &stderrPath })
  {
    if (!path->empty())
    {
      const int fd = ::open(path->c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      if (fd < 0)
      {
        throw Error(
          "'" + *path + "': cannot write the child's output (" + std::strerror(errno) + ")");
      }
      ::close(fd);
    }
  }
  FileActions files;
  if (!stdoutPath.empty())
  {
    posix_spawn_file_actions_addopen(
      &files.actions, 1, stdoutPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  if (!stderrPath.empty() && stderrPath == stdoutPath)
  {
    // One file for both, as the shell's "> log 2>&1": one open file, so that
    // neither stream overwrites the other.
    posix_spawn_file_actions_adddup2(&files.actions, 1, 2);
  }
  else if (!stderrPath.empty())
  {
    posix_spawn_file_actions_addopen(
      &files.actions, 2, stderrPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  const double start = nowS();
  const pid_t pid = spawn(arguments, files);
  return waitFor(pid, arguments.front(), start);
}

ChildProcess::ChildProcess(const std::vector<std::string>& arguments)
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
  FileActions files;
  posix_spawn_file_actions_adddup2(&files.actions, output[1], 1);
  posix_spawn_file_actions_adddup2(&files.actions, errors[1], 2);
  // Its own process group, so that a kill reaches what it started too (a
  // shell's commands), and a terminal's Ctrl-C reaches the parent alone,
  // which ends the child as it unwinds.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  this->StartS = nowS();
  try
  {
    this->Pid = spawn(arguments, files, &attributes);
    posix_spawnattr_destroy(&attributes);
  }
  catch (...)
  {
    posix_spawnattr_destroy(&attributes);
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
      throw Error("'" + this->Program + "': sent nothing for " + timeout + " s");
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
    throw Error("'" + this->Program + "': the child process was finished already");
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
