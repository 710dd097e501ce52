#ifndef vimlop_CohortRowStatus_h
#define vimlop_CohortRowStatus_h

#include <string>
#include <vector>

namespace vimlop
{

class CohortFolder;
struct CohortRow;

/// @brief Where a row of a cohort stands.
enum class CohortRowState
{
  /// Never tried.
  NotRun,
  /// Its lock is held: it runs now (here, or on another node).
  Running,
  /// Its result is written.
  Complete,
  /// Its result is written and flagged as a failure by the command itself
  /// (register's contour-error flag, exit code 3): a result, not an error.
  Flagged,
  /// Its command ended with an error; the attempt's error says which.
  Failed,
  /// An attempt began and never ended (its runner was killed): no result.
  Interrupted,
  /// Its result was made for a row that has changed since: run it again.
  Changed
};

/// @brief "not run", "running", "complete", "flagged", "failed", "interrupted", "changed".
const char* toString(CohortRowState state);

/// @brief One attempt at a row: where and when it ran, what it cost, how it ended.
struct CohortAttempt
{
  /// Running until it ends, then Complete, Flagged, Failed, or Interrupted
  /// (stopped by the user).
  CohortRowState state = CohortRowState::Running;
  /// The machine it ran on, and the process that ran it (the cohort runner's).
  std::string host;
  int pid = 0;
  /// "<array job>_<task>" when it ran as a task of a Slurm job array; "" here.
  std::string slurmJob;
  /// UTC, ISO 8601 ("2026-12-05T10:33:10Z").
  std::string startedUtc;
  std::string endedUtc;
  /// The version of the VIMLOP that ran it (the runner's, which runs its own program).
  std::string vimlopVersion;
  /// Threads its command was given (0: all cores).
  int threads = 0;
  /// Its command's wall time, CPU time (user + system) and peak memory.
  double wallS = 0.0;
  double cpuS = 0.0;
  double peakResidentMiB = 0.0;
  /// How its command ended: exit code (-1 for a signal) and signal (0 for an exit).
  int exitCode = -1;
  int signal = 0;
  /// Why it failed, in one line (the command's own `vimlop: error:` line).
  std::string error;
};

/**
 * @brief A row's record, status/<id>.json: its attempts, oldest first, and
 * the digest (CohortRow::digest) of the row whose result is in jobs/<id>,
 * set when an attempt succeeds (empty before).
 */
struct CohortRowStatus
{
  std::string id;
  std::string digest;
  std::vector<CohortAttempt> attempts;

  /// @brief The latest attempt, or nullptr when there is none.
  const CohortAttempt* last() const { return attempts.empty() ? nullptr : &attempts.back(); }
};

/**
 * @brief Reads a row's record; an empty record (no attempts) when the file
 * does not exist.
 * @throws vimlop::Error naming the file when it is not a row record.
 */
CohortRowStatus readCohortRowStatus(const std::string& path);

/// @brief Writes a row's record atomically. @throws vimlop::Error when it cannot.
void writeCohortRowStatus(const CohortRowStatus& status, const std::string& path);

/**
 * @brief The state of `row` in `folder` now, from its result file, its
 * record (returned in `status` when given) and its lock.
 */
CohortRowState cohortRowState(
  const CohortFolder& folder, const CohortRow& row, CohortRowStatus* status = nullptr);

/**
 * @brief A row's lock (status/<id>.lock, flock): held while an attempt runs,
 * so that two runners (two `cohort run`, or Slurm tasks on two nodes of a
 * shared file system) never run one row at once, and a reader can tell a
 * running row from an interrupted one. It dies with its process.
 */
class CohortRowLock
{
public:
  /// @brief Tries to take the lock; held() says whether it did.
  explicit CohortRowLock(const std::string& path);
  ~CohortRowLock();
  CohortRowLock(const CohortRowLock&) = delete;
  CohortRowLock& operator=(const CohortRowLock&) = delete;
  bool held() const { return this->Fd >= 0; }

  /// @brief Whether another process holds the lock at `path` now.
  static bool heldElsewhere(const std::string& path);

private:
  int Fd = -1;
};

/// @brief Now, UTC, ISO 8601 to the second ("2026-12-05T10:33:10Z").
std::string utcNow();

/// @brief This machine's host name ("" when unknown).
std::string hostName();

} // namespace vimlop

#endif
