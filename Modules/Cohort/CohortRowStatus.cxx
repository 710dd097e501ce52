#include <vimlop/Cohort/CohortRowStatus.h>

#include <vimlop/Cohort/CohortFolder.h>
#include <vimlop/Cohort/CohortManifest.h>
#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/FileError.h>

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace vimlop
{

namespace fs = std::filesystem;
using nlohmann::json;

namespace
{

const CohortRowState allStates[] = { CohortRowState::NotRun, CohortRowState::Running,
  CohortRowState::Complete, CohortRowState::Flagged, CohortRowState::Failed,
  CohortRowState::Interrupted, CohortRowState::Changed };

CohortRowState stateFromString(const std::string& text, const std::string& path)
{
  for (CohortRowState state : allStates)
  {
    if (text == toString(state))
    {
      return state;
    }
  }
  throwFileError(path, "unknown row state '" + text + "'");
}

json attemptJson(const CohortAttempt& a)
{
  return { { "state", toString(a.state) }, { "host", a.host }, { "pid", a.pid },
    { "slurm_job", a.slurmJob }, { "started", a.startedUtc }, { "ended", a.endedUtc },
    { "vimlop_version", a.vimlopVersion }, { "threads", a.threads }, { "wall_s", a.wallS },
    { "cpu_s", a.cpuS }, { "peak_resident_mib", a.peakResidentMiB }, { "exit_code", a.exitCode },
    { "signal", a.signal }, { "error", a.error } };
}

CohortAttempt attemptFrom(const json& j, const std::string& path)
{
  CohortAttempt a;
  a.state = stateFromString(j.at("state").get<std::string>(), path);
  a.host = j.value("host", "");
  a.pid = j.value("pid", 0);
  a.slurmJob = j.value("slurm_job", "");
  a.startedUtc = j.value("started", "");
  a.endedUtc = j.value("ended", "");
  a.vimlopVersion = j.value("vimlop_version", "");
  a.threads = j.value("threads", 0);
  a.wallS = j.value("wall_s", 0.0);
  a.cpuS = j.value("cpu_s", 0.0);
  a.peakResidentMiB = j.value("peak_resident_mib", 0.0);
  a.exitCode = j.value("exit_code", -1);
  a.signal = j.value("signal", 0);
  a.error = j.value("error", "");
  return a;
}

} // namespace

const char* toString(CohortRowState state)
{
  switch (state)
  {
    case CohortRowState::NotRun:
      return "not run";
    case CohortRowState::Running:
      return "running";
    case CohortRowState::Complete:
      return "complete";
    case CohortRowState::Flagged:
      return "flagged";
    case CohortRowState::Failed:
      return "failed";
    case CohortRowState::Interrupted:
      return "interrupted";
    case CohortRowState::Changed:
      return "changed";
  }
  return "unknown";
}

CohortRowStatus readCohortRowStatus(const std::string& path)
{
  CohortRowStatus status;
  std::ifstream in(path);
  if (!in)
  {
    return status;
  }
  try
  {
    const json j = json::parse(in);
    status.id = j.at("id").get<std::string>();
    status.digest = j.at("digest").get<std::string>();
    for (const json& attempt : j.at("attempts"))
    {
      status.attempts.push_back(attemptFrom(attempt, path));
    }
  }
  catch (const json::exception& e)
  {
    throwFileError(path, std::string("not a cohort row record (") + e.what() + ")");
  }
  return status;
}

void writeCohortRowStatus(const CohortRowStatus& status, const std::string& path)
{
  json attempts = json::array();
  for (const CohortAttempt& a : status.attempts)
  {
    attempts.push_back(attemptJson(a));
  }
  const json j = { { "id", status.id }, { "digest", status.digest }, { "attempts", attempts } };
  writeFileAtomically(path, j.dump(2) + "\n");
}

CohortRowState cohortRowState(
  const CohortFolder& folder, const CohortRow& row, CohortRowStatus* statusOut)
{
  const CohortRowStatus status = readCohortRowStatus(folder.statusPath(row.id));
  if (statusOut)
  {
    *statusOut = status;
  }
  if (CohortRowLock::heldElsewhere(folder.lockPath(row.id)))
  {
    return CohortRowState::Running;
  }
  // The record's digest is that of the row whose result is in jobs/<id>:
  // it is set when an attempt succeeds, so a failed re-run of a changed row
  // never makes the old result pass for the new row's.
  const CohortAttempt* last = status.last();
  std::error_code error;
  if (fs::exists(folder.resultPath(row), error))
  {
    if (!status.digest.empty() && status.digest != row.digest())
    {
      return CohortRowState::Changed;
    }
    return last && last->state == CohortRowState::Flagged ? CohortRowState::Flagged
                                                          : CohortRowState::Complete;
  }
  if (!last)
  {
    return CohortRowState::NotRun;
  }
  switch (last->state)
  {
    case CohortRowState::Running:
    case CohortRowState::Interrupted:
      return CohortRowState::Interrupted;
    case CohortRowState::Failed:
      return CohortRowState::Failed;
    default:
      return CohortRowState::NotRun; // its result was removed since
  }
}

CohortRowLock::CohortRowLock(const std::string& path)
{
  this->Fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (this->Fd < 0)
  {
    throwFileError(path, std::string("cannot make the row's lock (") + std::strerror(errno) + ")");
  }
  if (::flock(this->Fd, LOCK_EX | LOCK_NB) != 0)
  {
    ::close(this->Fd);
    this->Fd = -1;
  }
}

CohortRowLock::~CohortRowLock()
{
  if (this->Fd >= 0)
  {
    ::close(this->Fd);
  }
}

bool CohortRowLock::heldElsewhere(const std::string& path)
{
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
  {
    return false;
  }
  const bool held = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  return held;
}

std::string utcNow()
{
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string hostName()
{
  char name[256] = {};
  if (::gethostname(name, sizeof(name) - 1) != 0)
  {
    return std::string();
  }
  return name;
}

} // namespace vimlop
