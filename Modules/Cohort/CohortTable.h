#ifndef vimlop_CohortTable_h
#define vimlop_CohortTable_h

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace vimlop
{

class CohortFolder;
struct CohortRowCommand;
struct CohortManifest;

/**
 * @brief Every row of a cohort in one table: its state, its figures (from
 * its result) and its provenance (VIMLOP version, options, input
 * checksums, host, times), as `vimlop cohort merge` writes it.
 *
 * The columns come in three groups: id, command, state and error; the
 * figures, in the order they first appear going down the manifest; the
 * provenance. A register row's figures are those of its result.json
 * (camera errors against the truth when it had one, contour and residual
 * errors, scale, the failure flag); a protocol's are the numbers of its
 * report, named by their path ("methods.vimlop.tre_mm.median"). Columns
 * that differ from run to run of the same rows (times, hosts, thread counts)
 * are listed in `volatileColumns`: the rest is the same, byte for byte,
 * whatever the machine, the thread count or the Slurm task a row ran in.
 */
struct CohortTable
{
  std::vector<std::string> columns;
  std::vector<std::string> volatileColumns;
  /// One object per manifest row, in its order: column -> value (absent: no value).
  std::vector<nlohmann::json> rows;

  /// @brief The values of `column` that are numbers, going down the rows.
  std::vector<double> numbers(const std::string& column) const;
  /// @brief The rows whose "state" is one of `states`.
  std::vector<const nlohmann::json*> rowsIn(const std::vector<std::string>& states) const;
  /// @brief The table as CSV (RFC 4180; numbers as in the JSON, absent values empty).
  std::string csv() const;
  /// @brief The table as JSON: {"format", "columns", "volatile_columns", "rows"}.
  nlohmann::json toJson() const;
};

/**
 * @brief Gathers the table of the cohort of `manifest` in `folder`.
 * @throws vimlop::Error when a row's result file exists but cannot be read.
 */
CohortTable mergeCohortTable(const CohortManifest& manifest, const CohortFolder& folder);

/**
 * @brief A row's figures for a progress line ("camera error 0.41 mm, contour
 * error 5.9 px"; "flagged: <reason>"); empty when it has none to say.
 */
std::string cohortRowSummary(const CohortRowCommand& command, const std::string& resultPath);

} // namespace vimlop

#endif
