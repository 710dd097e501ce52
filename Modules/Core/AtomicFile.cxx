#include <vimlop/Core/AtomicFile.h>

#include <vimlop/Core/FileError.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <unistd.h>

namespace vimlop
{

void syncToDisk(const std::string& path)
{
  // A folder is opened read-only; fsync of its descriptor makes its entries
  // (a rename into it) durable, as fsync of a file makes its bytes.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0)
  {
    const std::string reason = std::strerror(errno);
    if (fd >= 0)
    {
      ::close(fd);
    }
    throwFileError(path, "cannot flush it to disk (" + reason + ")");
  }
  ::close(fd);
}

void writeFileAtomically(const std::string& path, const std::string& contents)
{
  const std::filesystem::path target(path);
  if (target.has_parent_path())
  {
    // A failure here shows as the write's failure below, which names the file.
    std::error_code ec;
    std::filesystem::create_directories(target.parent_path(), ec);
  }
  // Beside the target, so the rename stays on one file system and is atomic.
  const std::string temporary = path + ".part";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  bool written = fd >= 0;
  for (std::size_t done = 0; written && done < contents.size();)
  {
    const ssize_t n = ::write(fd, contents.data() + done, contents.size() - done);
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    written = n > 0;
    done += written ? static_cast<std::size_t>(n) : 0;
  }
  // The bytes reach the disk before the rename publishes them: after a power
  // cut the file is the old one or the whole new one, never an empty one.
  written = written && ::fsync(fd) == 0;
  const std::string reason = std::strerror(errno);
  if (fd >= 0)
  {
    written = ::close(fd) == 0 && written;
  }
  if (!written)
  {
    std::remove(temporary.c_str());
    throwFileError(path, "cannot write the file (" + reason + ")");
  }
  std::error_code ec;
  std::filesystem::rename(temporary, target, ec);
  if (ec)
  {
    std::remove(temporary.c_str());
    throwFileError(path, "cannot write the file (" + ec.message() + ")");
  }
  syncToDisk(target.has_parent_path() ? target.parent_path().string() : std::string("."));
}

std::string readWholeFile(const std::string& path)
{
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  std::string bytes;
  int error = fd < 0 ? errno : 0;
  char buffer[65536];
  while (error == 0)
  {
    const ssize_t n = ::read(fd, buffer, sizeof(buffer));
    if (n > 0)
    {
      bytes.append(buffer, static_cast<size_t>(n));
    }
    else if (n == 0)
    {
      break;
    }
    else if (errno != EINTR)
    {
      error = errno; // a folder: EISDIR
    }
  }
  if (fd >= 0)
  {
    ::close(fd);
  }
  if (error != 0)
  {
    throwFileError(path, std::string("cannot read it (") + std::strerror(error) + ")");
  }
  return bytes;
}

} // namespace vimlop
