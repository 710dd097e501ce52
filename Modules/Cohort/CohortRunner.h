#ifndef vimlop_CohortRunner_h
#define vimlop_CohortRunner_h

#include <vimlop/Cohort/CohortRowStatus.h>

#include <functional>
#include <string>
#include <vector>

namespace vimlop
{

class CohortFolder;
struct CohortManifest;

/// @brief What became of one row in a run.
struct CohortRowOutcome
{
  std::string id;
  /// Complete, Flagged, Failed or Interrupted when it ran; Running when
  /// another runner held it, so this one left it alone.
  CohortRowState state = CohortRowState::NotRun;
  /// Its attempt (empty when it did not run here).
  CohortAttempt attempt;
  /// The row's own figures for a progress line, e.g. "camera error 0.41 mm"
  /// (empty when its result has none).
  std::string summary;
};

/// @brief How runCohort() runs a cohort's rows on this machine.
struct CohortRunOptions
{
  /// Rows run at once, each its own process. Default 1; at least 1.
  int jobs = 1;
  /// Threads each row's command gets (its --threads, unless the row sets
  /// one); 0: this machine's cores shared among the `jobs` (at least 1).
  /// Results do not depend on it (Documentation/Cohorts.md, determinism).
  int threadsPerJob = 0;
  /// Only the rows of these ids (in the manifest's order); empty: every row.
  std::vector<std::string> rows;
  /// Only rows that failed or were interrupted before; rows never tried wait.
  bool onlyFailed = false;
  /// The `vimlop` program the rows run (default: this process's own program).
  std::string program;
  /// The Slurm array task this runs as ("<job>_<task>"), recorded in each attempt.
  std::string slurmJob;
  /// Start a private X display (Xvfb) for the rows when DISPLAY is not set:
  /// rows that render (register, most protocols) need one.
  bool virtualDisplay = true;
  /// Called after each row ran (or was left to another runner), from the
  /// thread that ran it, one call at a time; `done` counts the rows so far.
  std::function<void(const CohortRowOutcome& outcome, int done, int total)> onRowDone;
  /// Called with notes on the run (rows skipped, the display), one at a time.
  std::function<void(const std::string& note)> onNote;
  /// Asked while rows run: false stops them (SIGTERM to their commands, which
  /// stop as on Ctrl-C, then SIGKILL after 10 s) and starts no more.
  std::function<bool()> keepGoing;
};

/// @brief What a run did, row by row.
struct CohortRunReport
{
  /// Rows selected (all of the manifest, or those asked for).
  int selected = 0;
  /// Of those, rows whose result was there before the run (skipped).
  int alreadyComplete = 0;
  /// The rows this run tried, in the manifest's order.
  std::vector<CohortRowOutcome> outcomes;
  /// True when keepGoing() stopped the run.
  bool interrupted = false;

  /// @brief How many of `outcomes` are in `state`.
  int count(CohortRowState state) const;
};

/**
 * @brief Runs the rows of `manifest` that have no result yet in `folder`
 * (prepared by CohortFolder::prepare), `jobs` at a time, each as a child
 * process of `vimlop` in the manifest's folder with its output in
 * jobs/<id>, its log in logs/<id>.log and its attempt in status/<id>.json.
 *
 * Complete rows are skipped, so a run that was interrupted or killed
 * resumes where it was; a row's lock keeps two runners off one row; a
 * failed row does not stop the others. Rows end with their runner, even
 * when it is killed outright (their results are written atomically or not
 * at all).
 * @throws vimlop::Error when an id in `options.rows` is not in the manifest,
 * or a row's files cannot be written.
 */
CohortRunReport runCohort(
  const CohortManifest& manifest, const CohortFolder& folder, const CohortRunOptions& options);

/**
 * @brief The one line that says why a row's command failed, from its log:
 * its last `vimlop: error:` line, else how it ended and its last line.
 */
std::string cohortFailureLine(const std::string& logText, int exitCode, int signal);

} // namespace vimlop

#endif
