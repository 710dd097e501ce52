#ifndef vimlop_CohortManifest_h
#define vimlop_CohortManifest_h

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vimlop
{

/**
 * @brief One job of a cohort: a `vimlop` command (`register`, or a protocol
 * of `vimlop evaluate`) with its options, run into its own output folder.
 */
struct CohortRow
{
  /// Its name: the folder of its output (jobs/<id>) and its row in the
  /// merged table. Letters, digits, '.', '_' and '-'; unique in a manifest.
  std::string id;
  /// The command's words, e.g. {"register"} or {"evaluate", "synthetic"}.
  std::vector<std::string> command;
  /// Its options, in the manifest's order: the option's long name (without
  /// "--") and its value; an empty value is a flag given bare (`no-video`).
  std::vector<std::pair<std::string, std::string>> options;
  /// The manifest line (CSV) or the position in "rows" (JSON, from 1) it
  /// came from, for messages.
  int line = 0;

  /// @brief The command's words joined by spaces ("evaluate synthetic").
  std::string commandName() const;
  /// @brief Its command line after `vimlop`: the words, then "--name value"
  /// (or "--name") for each option. The cohort adds the output option.
  std::vector<std::string> arguments() const;
  /**
   * @brief A digest of what it runs (command and options): a result made
   * for a row that has changed since is not that row's result.
   */
  std::string digest() const;
};

/// @brief Whether an option of a command takes a value, is a bare flag, or does not exist.
enum class CohortOptionKind
{
  Unknown,
  Flag,
  Value
};

/**
 * @brief What the program knows of its own commands, for checking a manifest
 * before any row runs: `commandKnown` answers for a command's words,
 * `optionKind` for one of its options (a long name without "--"), and
 * `suggestion` may name the nearest option for a misspelt one (empty: none).
 * The command-line program answers from its own parser.
 */
struct CohortCommandCatalog
{
  std::function<bool(const std::vector<std::string>& command)> commandKnown;
  std::function<CohortOptionKind(const std::vector<std::string>& command, const std::string& name)>
    optionKind;
  std::function<std::string(const std::vector<std::string>& command, const std::string& name)>
    suggestion;
};

/**
 * @brief A cohort's jobs, one row each, read from a CSV or JSON manifest
 * (Documentation/Cohorts.md gives both layouts).
 *
 * Relative paths in its rows are relative to the manifest's folder: every
 * row runs there, so that its result records its input paths as the
 * manifest gives them, whatever folder or machine it ran on.
 */
struct CohortManifest
{
  /// The file it was read from, absolute.
  std::string path;
  /// The folder its rows run in: the manifest's own, absolute.
  std::string folder;
  std::vector<CohortRow> rows;

  /// @brief The row named `id`, or nullptr.
  const CohortRow* find(const std::string& id) const;
};

/**
 * @brief Reads a manifest: `.csv` (a header with the columns `id` and
 * `command`, any option as a column of its own, and `options` for further
 * flags as on a command line) or `.json` (`{"rows": [{"id": ..,
 * "command": .., <option>: .., "options": {..} or [..]}]}`).
 *
 * Without a `catalog`, an option valued true or false is a flag (given
 * bare, or left out) and every other a value.
 *
 * Every row is checked before any runs: an id that is missing, repeated or
 * not a safe folder name, an unknown command or option (with `catalog`),
 * a flag given a value other than true/false, a value option without one,
 * and the options the cohort sets itself (out, force, serve, print-options)
 * are refused, naming the manifest, the line and the row.
 * @throws vimlop::Error naming the file: it cannot be read, its format is
 * unknown, or a row is refused.
 */
CohortManifest readCohortManifest(
  const std::string& path, const CohortCommandCatalog& catalog = CohortCommandCatalog());

} // namespace vimlop

#endif
