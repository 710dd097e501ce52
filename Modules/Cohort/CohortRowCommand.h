#ifndef vimlop_CohortRowCommand_h
#define vimlop_CohortRowCommand_h

#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief How a cohort runs one kind of row (a `vimlop` command) and reads
 * what it wrote: the one place that knows each command's output.
 */
struct CohortRowCommand
{
  /// Where the command's --out points.
  enum class Output
  {
    /// The row's folder itself (jobs/<id>): commands that write a folder.
    Folder,
    /// `resultFile` inside the row's folder: commands that write one file.
    FileInFolder
  };
  /// What its result file holds, for the merged table.
  enum class Figures
  {
    /// A result folder's result.json (vimlop register).
    Registration,
    /// A protocol's report (vimlop evaluate ...): its numbers as they are.
    ProtocolReport
  };

  /// The command's words, e.g. {"evaluate", "synthetic"}.
  std::vector<std::string> words;
  Output output = Output::Folder;
  /// The file, inside the row's folder, that the command writes last and
  /// atomically: its presence says that the row is complete.
  std::string resultFile;
  /// The exit code that means "complete, but flagged as a failure"
  /// (register: 3); -1 when the command has none.
  int flaggedExitCode = -1;
  Figures figures = Figures::ProtocolReport;
  /// Whether it takes --threads (the cohort gives each row its share of the cores).
  bool takesThreads = true;
  /// Whether it takes --force, which it needs to replace an earlier result
  /// folder (a row run again because it changed).
  bool takesForce = false;
  /// Rough wall time of one row at default settings on 2 cores, s: Slurm's
  /// default chunking puts enough rows in an array task for it to last at
  /// least 20 s (Documentation/Cohorts.md).
  double typicalSeconds = 30.0;
};

/// @brief Every command a cohort row may run: register and the protocols of `vimlop evaluate`.
const std::vector<CohortRowCommand>& cohortRowCommands();

/// @brief The command of `words`, or nullptr when a cohort cannot run it.
const CohortRowCommand* findCohortRowCommand(const std::vector<std::string>& words);

} // namespace vimlop

#endif
