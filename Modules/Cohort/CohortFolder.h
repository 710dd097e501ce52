#ifndef vimlop_CohortFolder_h
#define vimlop_CohortFolder_h

#include <string>

namespace vimlop
{

struct CohortCommandCatalog;
struct CohortManifest;
struct CohortRow;

/**
 * @brief The layout of a cohort folder (Documentation/Cohorts.md), the one
 * place that names its files:
 *
 *     cohort.json           the manifest it runs (path, folder) and the VIMLOP that made it
 *     manifest.csv|json     a copy of that manifest, as last run or submitted
 *     jobs/<id>/            each row's output (a result folder, a protocol's files)
 *     status/<id>.json      each row's attempts: host, times, cost, exit code, error
 *     status/<id>.lock      held (flock) while the row runs, wherever it runs
 *     logs/<id>.log         what the row's command printed, last attempt
 *     slurm/                batch scripts, submissions and Slurm's logs
 *     table.csv, table.json, report/index.html   the merged table and its page
 */
class CohortFolder
{
public:
  /// @brief The cohort folder `root` (made absolute; need not exist yet).
  explicit CohortFolder(const std::string& root);

  const std::string& root() const { return this->Root; }
  std::string rowFolder(const std::string& id) const;
  /// @brief The file whose presence says that `row` is complete.
  std::string resultPath(const CohortRow& row) const;
  /// @brief What the row's command gets as --out.
  std::string outArgument(const CohortRow& row) const;
  std::string statusPath(const std::string& id) const;
  std::string lockPath(const std::string& id) const;
  std::string logPath(const std::string& id) const;
  std::string recordPath() const;
  /// @brief The manifest's copy: manifest.csv or manifest.json.
  std::string manifestCopyPath(const std::string& manifestPath) const;
  std::string slurmFolder() const;
  std::string tableCsvPath() const;
  std::string tableJsonPath() const;
  std::string reportFolder() const;

  /**
   * @brief Makes the folder (and its parts) for `manifest`: writes
   * cohort.json and the manifest's copy.
   * @throws vimlop::Error when `root` is something other than a cohort
   * folder (a file, or a folder with other files: a mistyped --out must not
   * fill a user's folder), when it holds the cohort of another manifest, or
   * when it cannot be written.
   */
  void prepare(const CohortManifest& manifest) const;

  /**
   * @brief The manifest of the cohort in this folder: its copy here, read
   * with `catalog`, with the original's path and folder (where rows run),
   * as cohort.json names them.
   * @throws vimlop::Error when the folder is no cohort folder.
   */
  CohortManifest manifest(const CohortCommandCatalog& catalog) const;

private:
  std::string Root;
};

} // namespace vimlop

#endif
