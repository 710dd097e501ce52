#include <vimlop/Evaluation/ChildProcess.h>

#include <vimlop/Core/Error.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
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

/// posix_spawn's file actions, destroyed on every path out.
struct FileActions
{
  posix_spawn_file_actions_t actions;
  FileActions() { posix_spawn_file_actions_init(&this->actions); }
  ~FileActions() { posix_spawn_file_actions_destroy(&this->actions); }
  FileActions(const FileActions&) = delete;
  FileActions& operator=(const FileActions&) = delete;
};

} // namespace

ChildProcessResult runChildProcess(const std::vector<std::string>& arguments,
  const std::string& stdoutPath, const std::string& stderrPath)
{
  if (arguments.empty() || arguments.front().empty())
  {
    throw Error("child process: no program given");
  }
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
  posix_spawn_file_actions_addopen(&files.actions, 0, "/dev/null", O_RDONLY, 0);
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
  std::vector<char*> argv;
  for (const std::string& a : arguments)
  {
    argv.push_back(const_cast<char*>(a.c_str()));
  }
  argv.push_back(nullptr);

  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int spawned = arguments.front().find('/') == std::string::npos
    ? posix_spawnp(&pid, argv[0], &files.actions, nullptr, argv.data(), environ)
    : posix_spawn(&pid, argv[0], &files.actions, nullptr, argv.data(), environ);
  if (spawned != 0)
  {
    throw Error("'" + arguments.front() + "': cannot start it (" + std::strerror(spawned) + ")");
  }
  int status = 0;
  rusage usage{};
  pid_t waited = 0;
  do
  {
    waited = ::wait4(pid, &status, 0, &usage);
  } while (waited < 0 && errno == EINTR);
  ChildProcessResult result;
  result.wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (waited != pid)
  {
    throw Error(
      "'" + arguments.front() + "': lost the child process (" + std::strerror(errno) + ")");
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
