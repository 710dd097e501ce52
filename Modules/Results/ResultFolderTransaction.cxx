#include <vimlop/Results/ResultFolderTransaction.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace vimlop
{

namespace fs = std::filesystem;

namespace
{

/// The folder as named, without trailing separators ("out/" is "out").
std::string withoutTrailingSeparators(std::string folder)
{
  while (folder.size() > 1 && folder.back() == '/')
  {
    folder.pop_back();
  }
  return folder;
}

bool looksLikeAResultFolder(const fs::path& folder)
{
  std::error_code ec;
  return fs::is_empty(folder, ec) || fs::exists(folder / "result.json", ec) ||
    fs::exists(folder / "registered-poses.json", ec) ||
    fs::exists(folder / "vimlop-export.json", ec);
}

/// The process id the lock's holder wrote into it, or "" when unreadable.
std::string holderOf(int fd)
{
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof(text) - 1, 0);
  std::string pid(text, n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' '))
  {
    pid.pop_back();
  }
  return pid;
}

/// Takes the lock file's flock without waiting; returns its descriptor.
int lockOrFail(const std::string& folder, const std::string& lockPath)
{
  // A finishing holder unlinks the lock file while it still holds it; a
  // lock taken on that unlinked file would be no lock, so take it again on
  // the file the path names now.
  for (int attempt = 0; attempt < 100; ++attempt)
  {
    const int fd = ::open(lockPath.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
    {
      throwFileError(
        folder, "cannot create the lock file '" + lockPath + "' (" + std::strerror(errno) + ")");
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0)
    {
      const int error = errno;
      const std::string holder = holderOf(fd);
      ::close(fd);
      if (error == EWOULDBLOCK)
      {
        throwFileError(folder,
          "another run" + (holder.empty() ? std::string() : " (process " + holder + ")") +
            " is writing this result folder; wait for it to end or choose another --out");
      }
      throwFileError(folder, "cannot lock '" + lockPath + "' (" + std::strerror(error) + ")");
    }
    struct stat opened = {};
    struct stat named = {};
    if (::fstat(fd, &opened) == 0 && ::stat(lockPath.c_str(), &named) == 0 &&
      opened.st_ino == named.st_ino && opened.st_dev == named.st_dev)
    {
      const std::string pid = std::to_string(::getpid()) + "\n";
      if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) < 0)
      {
        // The pid is for messages only; the lock holds without it.
      }
      return fd;
    }
    ::close(fd);
  }
  throwFileError(folder, "cannot take the lock '" + lockPath + "': it keeps being replaced");
}

/// fsync of every file and folder under `root`, and of `root`.
void syncTree(const fs::path& root)
{
  std::error_code ec;
  for (fs::recursive_directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec))
  {
    if (it->is_regular_file() || it->is_directory())
    {
      syncToDisk(it->path().string());
    }
  }
  if (ec)
  {
    throwFileError(root.string(), "cannot list the folder to flush it (" + ec.message() + ")");
  }
  syncToDisk(root.string());
}

} // namespace

ResultFolderTransaction::ResultFolderTransaction(
  const std::string& folder, Existing existing, std::string* note)
  : Folder(withoutTrailingSeparators(folder))
  , Staging(this->Folder + ".partial")
  , LockPath(this->Folder + ".lock")
{
  const fs::path path(this->Folder);
  const std::string name = path.filename().string();
  if (this->Folder.empty() || name.empty() || name == "." || name == ".." || this->Folder == "/")
  {
    throwFileError(
      folder, "name a folder of its own for the result (it is written beside, then renamed)");
  }
  std::error_code ec;
  const auto checkExisting = [&]
  {
    if (!fs::exists(path, ec))
    {
      return;
    }
    if (!fs::is_directory(path, ec))
    {
      throwFileError(this->Folder, "exists and is not a folder; choose another --out");
    }
    if (existing == Existing::Refuse)
    {
      throwFileError(this->Folder, "exists; choose another --out or add --force to replace it");
    }
    if (!looksLikeAResultFolder(path))
    {
      throwFileError(this->Folder,
        "exists and is not a VIMLOP result folder (no result.json, registered-poses.json or "
        "vimlop-export.json); "
        "refusing to replace it");
    }
  };
  checkExisting();
  if (path.has_parent_path())
  {
    fs::create_directories(path.parent_path(), ec);
    if (ec)
    {
      throwFileError(this->Folder, "cannot create the folder it goes in (" + ec.message() + ")");
    }
  }
  this->LockFd = lockOrFail(this->Folder, this->LockPath);
  try
  {
    checkExisting(); // again, now that no other run can change it
    if (fs::exists(this->Staging, ec))
    {
      fs::remove_all(this->Staging, ec);
      if (ec)
      {
        throwFileError(this->Staging,
          "cannot remove this unfinished result of an earlier run (" + ec.message() + ")");
      }
      if (note)
      {
        *note = "removed '" + this->Staging + "', left by a run into '" + this->Folder +
          "' that did not finish";
      }
    }
    if (!fs::create_directory(this->Staging, ec) || ec)
    {
      throwFileError(this->Staging,
        "cannot create the folder the result is written to (" +
          (ec ? ec.message() : std::string("it exists")) + ")");
    }
  }
  catch (...)
  {
    ::close(this->LockFd);
    throw;
  }
}

ResultFolderTransaction::~ResultFolderTransaction()
{
  std::error_code ec;
  if (!this->Committed && !this->Keep)
  {
    fs::remove_all(this->Staging, ec);
  }
  // Unlinked while still held: a run waiting on the same path takes a fresh
  // file (see lockOrFail()).
  ::unlink(this->LockPath.c_str());
  ::close(this->LockFd);
}

void ResultFolderTransaction::commit()
{
  // Until the rename, a failure leaves the result where it was written.
  const auto failKeeping = [this](const std::string& problem)
  {
    this->Keep = true;
    throwFileError(this->Folder, problem + "; the result is in '" + this->Staging + "'");
  };
  try
  {
    syncTree(this->Staging);
  }
  catch (const Error& e)
  {
    failKeeping(std::string("cannot flush the result to disk: ") + e.what());
  }
  std::error_code ec;
  if (!fs::exists(this->Folder, ec))
  {
    if (std::rename(this->Staging.c_str(), this->Folder.c_str()) != 0)
    {
      failKeeping(
        std::string("cannot rename the result into place (") + std::strerror(errno) + ")");
    }
  }
  else if (::renameat2(
             AT_FDCWD, this->Staging.c_str(), AT_FDCWD, this->Folder.c_str(), RENAME_EXCHANGE) == 0)
  {
    // One step: the new result is in place, the old one where it was written.
    fs::remove_all(this->Staging, ec);
  }
  else
  {
    // A file system without the exchange: the old folder steps aside first,
    // so an interruption leaves the old result or none, never a mix.
    const std::string old = this->Folder + ".old";
    fs::remove_all(old, ec);
    if (std::rename(this->Folder.c_str(), old.c_str()) != 0 ||
      std::rename(this->Staging.c_str(), this->Folder.c_str()) != 0)
    {
      failKeeping(
        std::string("cannot replace the folder with the result (") + std::strerror(errno) + ")");
    }
    fs::remove_all(old, ec);
  }
  this->Committed = true;
  const fs::path parent = fs::path(this->Folder).parent_path();
  syncToDisk(parent.empty() ? std::string(".") : parent.string());
}

} // namespace vimlop
