#include <vimlop/Cohort/CohortRunner.h>

#include <vimlop/Cohort/CohortFolder.h>
#include <vimlop/Cohort/CohortManifest.h>
#include <vimlop/Cohort/CohortRowCommand.h>
#include <vimlop/Cohort/CohortTable.h>
#include <vimlop/Cohort/VirtualDisplay.h>
#include <vimlop/Core/ChildProcess.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/TaskPool.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include <unistd.h>

namespace vimlop
{

namespace fs = std::filesystem;

namespace
{

/// The end of a log (its last 64 KiB): enough for its last lines.
std::string logTail(const std::string& path)
{
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in)
  {
    return std::string();
  }
  const std::streamoff size = in.tellg();
  const std::streamoff keep = std::min<std::streamoff>(size, 65536);
  in.seekg(size - keep);
  std::string text(static_cast<size_t>(keep), '\0');
  in.read(text.data(), keep);
  return text;
}

std::vector<std::string> linesOf(const std::string& text)
{
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
  {
    // A progress line rewritten with \r: its last state.
    const size_t cr = line.find_last_of('\r', line.size() > 1 ? line.size() - 2 : 0);
    if (cr != std::string::npos && cr + 1 < line.size())
    {
      line = line.substr(cr + 1);
    }
    while (!line.empty() && (line.back() == '\r' || line.back() == ' '))
    {
      line.pop_back();
    }
    if (!line.empty())
    {
      lines.push_back(line);
    }
  }
  return lines;
}

/// The rows to consider: all, or those of `ids` (each must exist).
std::vector<const CohortRow*> selectedRows(
  const CohortManifest& manifest, const std::vector<std::string>& ids)
{
  std::vector<const CohortRow*> rows;
  if (ids.empty())
  {
    for (const CohortRow& row : manifest.rows)
    {
      rows.push_back(&row);
    }
    return rows;
  }
  const std::set<std::string> wanted(ids.begin(), ids.end());
  for (const std::string& id : wanted)
  {
    if (!manifest.find(id))
    {
      throw Error("no row '" + id + "' in the manifest '" + manifest.path + "'");
    }
  }
  for (const CohortRow& row : manifest.rows)
  {
    if (wanted.count(row.id))
    {
      rows.push_back(&row);
    }
  }
  return rows;
}

int threadsForEachJob(const CohortRunOptions& options)
{
  if (options.threadsPerJob > 0)
  {
    return options.threadsPerJob;
  }
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, cores / std::max(1, options.jobs));
}

/// Runs one row now (its lock taken here) and records its attempt.
CohortRowOutcome runRow(const CohortManifest& manifest, const CohortFolder& folder,
  const CohortRow& row, const CohortRunOptions& options, int threads)
{
  CohortRowOutcome outcome;
  outcome.id = row.id;
  const CohortRowLock lock(folder.lockPath(row.id));
  if (!lock.held())
  {
    outcome.state = CohortRowState::Running;
    return outcome;
  }
  // Another runner may have finished it between the selection and the lock.
  CohortRowStatus status;
  const CohortRowState before = cohortRowState(folder, row, &status);
  if (before == CohortRowState::Complete || before == CohortRowState::Flagged)
  {
    outcome.state = before;
    return outcome;
  }
  const CohortRowCommand& command = *findCohortRowCommand(row.command);
  CohortAttempt& attempt = status.attempts.emplace_back();
  status.id = row.id;
  attempt.host = hostName();
  attempt.pid = static_cast<int>(::getpid());
  attempt.slurmJob = options.slurmJob;
  attempt.startedUtc = utcNow();
  attempt.vimlopVersion = VIMLOP_VERSION;
  std::vector<std::string> arguments = { options.program };
  for (const std::string& word : row.arguments())
  {
    arguments.push_back(word);
  }
  const bool rowSetsThreads = std::any_of(row.options.begin(), row.options.end(),
    [](const auto& option) { return option.first == "threads"; });
  attempt.threads = command.takesThreads && !rowSetsThreads ? threads : 0;
  if (attempt.threads > 0)
  {
    arguments.insert(arguments.end(), { "--threads", std::to_string(threads) });
  }
  arguments.insert(arguments.end(), { "--out", folder.outArgument(row) });
  if (command.takesForce)
  {
    arguments.push_back("--force");
  }
  writeCohortRowStatus(status, folder.statusPath(row.id));
  if (command.output == CohortRowCommand::Output::FileInFolder)
  {
    fs::create_directories(folder.rowFolder(row.id));
  }

  ChildProcessOptions child;
  child.stdoutPath = folder.logPath(row.id);
  child.stderrPath = child.stdoutPath;
  child.workingDirectory = manifest.folder;
  child.endsWithParent = true;
  child.keepRunning = options.keepGoing ? options.keepGoing : [] { return true; };
  ChildProcessResult ended;
  try
  {
    ended = runChildProcess(arguments, child);
  }
  catch (const Error& e)
  {
    ended.exitCode = -1;
    attempt.error = e.what();
  }
  attempt.endedUtc = utcNow();
  attempt.wallS = ended.wallS;
  attempt.cpuS = ended.userCpuS + ended.systemCpuS;
  attempt.peakResidentMiB = ended.peakResidentMiB;
  attempt.exitCode = ended.exitCode;
  attempt.signal = ended.signal;
  std::error_code error;
  const bool written = fs::exists(folder.resultPath(row), error);
  if (ended.stopped)
  {
    attempt.state = CohortRowState::Interrupted;
    attempt.error = "stopped before its end";
  }
  else if (written && (ended.exitCode == 0 || ended.exitCode == command.flaggedExitCode))
  {
    attempt.state = ended.exitCode == 0 ? CohortRowState::Complete : CohortRowState::Flagged;
    status.digest = row.digest();
    outcome.summary = cohortRowSummary(command, folder.resultPath(row));
  }
  else
  {
    attempt.state = CohortRowState::Failed;
    if (attempt.error.empty())
    {
      attempt.error = ended.exitCode == 0
        ? "ended without writing its result '" + command.resultFile + "'"
        : cohortFailureLine(logTail(folder.logPath(row.id)), ended.exitCode, ended.signal);
    }
  }
  writeCohortRowStatus(status, folder.statusPath(row.id));
  outcome.state = attempt.state;
  outcome.attempt = attempt;
  return outcome;
}

} // namespace

int CohortRunReport::count(CohortRowState state) const
{
  return static_cast<int>(std::count_if(this->outcomes.begin(), this->outcomes.end(),
    [&](const CohortRowOutcome& o) { return o.state == state; }));
}

std::string cohortFailureLine(const std::string& logText, int exitCode, int signal)
{
  const std::vector<std::string> lines = linesOf(logText);
  const std::string prefix = "vimlop: error: ";
  for (auto line = lines.rbegin(); line != lines.rend(); ++line)
  {
    if (line->compare(0, prefix.size(), prefix) == 0)
    {
      return line->substr(prefix.size());
    }
  }
  std::string how = signal != 0
    ? "ended by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")"
    : "exited with code " + std::to_string(exitCode);
  if (!lines.empty())
  {
    how += "; its last line: '" + lines.back().substr(0, 300) + "'";
  }
  return how;
}

CohortRunReport runCohort(
  const CohortManifest& manifest, const CohortFolder& folder, const CohortRunOptions& options)
{
  if (options.jobs < 1)
  {
    throw Error("cohort: at least 1 job at a time, not " + std::to_string(options.jobs));
  }
  const auto note = [&](const std::string& text)
  {
    if (options.onNote)
    {
      options.onNote(text);
    }
  };
  CohortRunReport report;
  std::vector<const CohortRow*> toRun;
  for (const CohortRow* row : selectedRows(manifest, options.rows))
  {
    ++report.selected;
    const CohortRowState state = cohortRowState(folder, *row);
    if (state == CohortRowState::Complete || state == CohortRowState::Flagged)
    {
      ++report.alreadyComplete;
    }
    else if (state == CohortRowState::Running)
    {
      note("'" + row->id + "' runs elsewhere (its lock is held); left to that run");
    }
    else if (!options.onlyFailed || state == CohortRowState::Failed ||
      state == CohortRowState::Interrupted)
    {
      toRun.push_back(row);
    }
  }
  if (toRun.empty())
  {
    return report;
  }
  CohortRunOptions settings = options;
  if (settings.program.empty())
  {
    settings.program = currentExecutablePath();
  }
  std::unique_ptr<VirtualDisplay> display;
  const char* given = std::getenv("DISPLAY");
  if (settings.virtualDisplay && (!given || !*given))
  {
    try
    {
      display = std::make_unique<VirtualDisplay>();
      note("rows render on a private X display " + display->name() + " (Xvfb)");
    }
    catch (const Error& e)
    {
      note(std::string("no X display: ") + e.what() +
        "; rows that render will fail (install the 'xvfb' package)");
    }
  }
  const int threads = threadsForEachJob(settings);
  const int total = static_cast<int>(toRun.size());
  std::vector<CohortRowOutcome> outcomes(toRun.size());
  std::mutex reporting;
  int done = 0;
  TaskPool pool(std::min(settings.jobs, total));
  pool.run(total,
    [&](int i)
    {
      if (settings.keepGoing && !settings.keepGoing())
      {
        outcomes[i].id = toRun[i]->id;
        outcomes[i].state = CohortRowState::NotRun;
        return;
      }
      outcomes[i] = runRow(manifest, folder, *toRun[i], settings, threads);
      const std::lock_guard<std::mutex> hold(reporting);
      ++done;
      if (settings.onRowDone)
      {
        settings.onRowDone(outcomes[i], done, total);
      }
    });
  report.interrupted = settings.keepGoing && !settings.keepGoing();
  for (CohortRowOutcome& outcome : outcomes)
  {
    if (outcome.state != CohortRowState::NotRun)
    {
      report.outcomes.push_back(std::move(outcome));
    }
  }
  return report;
}

} // namespace vimlop
