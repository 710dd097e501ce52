#include <vimlop/Cohort/CohortTable.h>

#include <vimlop/Cohort/CohortFolder.h>
#include <vimlop/Cohort/CohortManifest.h>
#include <vimlop/Cohort/CohortRowCommand.h>
#include <vimlop/Cohort/CohortRowStatus.h>
#include <vimlop/Cohort/CommandLineWords.h>
#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/Sha256.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TextFormat.h>

#include <algorithm>
#include <filesystem>
#include <set>

namespace vimlop
{

namespace fs = std::filesystem;
using nlohmann::json;

namespace
{

/// Keys of a protocol's report whose values are times or machine facts:
/// their columns differ between two runs of the same row.
bool volatileKey(const std::string& key)
{
  static const std::set<std::string> keys = { "runtime_s", "times_ms", "timings", "machine",
    "wall_s", "cpu_s", "peak_resident_mib", "load_average", "result_s", "seconds" };
  return keys.count(key) > 0;
}

json readJsonFile(const std::string& path)
{
  try
  {
    return json::parse(readWholeFile(path));
  }
  catch (const json::exception& e)
  {
    throwFileError(path, std::string("not valid JSON (") + e.what() + ")");
  }
}

/// A figure of a row, and whether it changes from run to run.
struct Figure
{
  std::string name;
  json value;
  bool isVolatile = false;
};

void addSummaryOf(std::vector<Figure>& figures, const std::string& name, const json& values)
{
  std::vector<double> numbers;
  if (values.is_array())
  {
    for (const json& v : values)
    {
      if (v.is_number())
      {
        numbers.push_back(v.get<double>());
      }
    }
  }
  if (numbers.empty())
  {
    return;
  }
  const Summary s = summarize(numbers);
  figures.push_back({ name + "_mean", s.mean });
  figures.push_back({ name + "_max", s.max });
}

/// The figures of a result folder's result.json.
std::vector<Figure> registrationFigures(const json& result)
{
  std::vector<Figure> figures;
  const auto copy = [&](const char* name, const json& value)
  {
    if (!value.is_null())
    {
      figures.push_back({ name, value });
    }
  };
  const auto at = [&](const json& object, const char* key)
  { return object.is_object() && object.contains(key) ? object.at(key) : json(); };
  const json confidence = at(result, "confidence");
  copy("frames", result.contains("frames") ? json(result.at("frames").size()) : json());
  copy("points", at(at(result, "points"), "count"));
  copy("point_inliers", at(at(result, "points"), "inliers"));
  copy("scale", at(at(result, "transform"), "scale"));
  copy("iterations", at(result, "iterations"));
  copy("termination", at(result, "termination"));
  copy("residual_error_mm", at(result, "residual_error_mm"));
  copy("contour_error_px", at(result, "contour_error_px"));
  copy("contour_error_inliers_px", at(result, "contour_error_inliers_px"));
  copy("flagged", at(confidence, "failure"));
  copy("failure_reason", at(confidence, "failure_reason"));
  copy("init", at(confidence, "init"));
  copy("candidates", at(confidence, "candidates"));
  const json truth = at(result, "ground_truth");
  addSummaryOf(figures, "camera_position_error_mm", at(truth, "camera_position_error_mm"));
  addSummaryOf(figures, "camera_angle_error_deg", at(truth, "camera_angle_error_deg"));
  copy("tre_mm", at(truth, "tre_mm"));
  if (result.contains("runtime_s"))
  {
    figures.push_back({ "runtime_s", result.at("runtime_s"), true });
  }
  return figures;
}

/// Every number, text and truth value of a protocol's report (arrays left
/// out), named by its path.
void flatten(const json& value, const std::string& path, bool isVolatile, std::vector<Figure>& out)
{
  if (value.is_object())
  {
    for (const auto& [key, item] : value.items())
    {
      flatten(item, path.empty() ? key : path + "." + key, isVolatile || volatileKey(key), out);
    }
  }
  else if (value.is_number() || value.is_string() || value.is_boolean())
  {
    out.push_back({ path, value, isVolatile });
  }
}

/// The provenance a result records: VIMLOP's version, the settings' digest,
/// the inputs' checksums.
std::vector<Figure> resultProvenance(const json& result)
{
  std::vector<Figure> provenance;
  if (result.contains("versions") && result.at("versions").contains("vimlop"))
  {
    provenance.push_back({ "vimlop_version", result.at("versions").at("vimlop") });
  }
  else if (result.contains("vimlop_version"))
  {
    provenance.push_back({ "vimlop_version", result.at("vimlop_version") });
  }
  if (result.contains("parameters") && result.at("parameters").is_object())
  {
    // The thread count is the one setting that may differ (results do not depend on it).
    json parameters = result.at("parameters");
    parameters.erase("threads");
    Sha256 sha;
    sha.update(parameters.dump());
    provenance.push_back({ "parameters_sha256", sha.hex() });
  }
  if (result.contains("inputs") && result.at("inputs").is_array())
  {
    for (const json& input : result.at("inputs"))
    {
      if (input.contains("role") && input.contains("sha256"))
      {
        provenance.push_back(
          { "input." + input.at("role").get<std::string>() + ".sha256", input.at("sha256") });
      }
    }
  }
  return provenance;
}

/// One cell of CSV: quoted when it holds a separator, a quote, a line break
/// or blanks at its ends.
std::string csvCell(const json& value)
{
  if (value.is_null())
  {
    return std::string();
  }
  const std::string text = value.is_string() ? value.get<std::string>() : value.dump();
  const bool quote = text.find_first_of(",\"\n\r") != std::string::npos ||
    (!text.empty() && (text.front() == ' ' || text.back() == ' '));
  if (!quote)
  {
    return text;
  }
  std::string quoted = "\"";
  for (char c : text)
  {
    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  }
  return quoted + "\"";
}

} // namespace

std::vector<double> CohortTable::numbers(const std::string& column) const
{
  std::vector<double> values;
  for (const json& row : this->rows)
  {
    if (row.contains(column) && row.at(column).is_number())
    {
      values.push_back(row.at(column).get<double>());
    }
  }
  return values;
}

std::vector<const json*> CohortTable::rowsIn(const std::vector<std::string>& states) const
{
  std::vector<const json*> found;
  for (const json& row : this->rows)
  {
    const std::string state = row.value("state", "");
    if (std::find(states.begin(), states.end(), state) != states.end())
    {
      found.push_back(&row);
    }
  }
  return found;
}

std::string CohortTable::csv() const
{
  std::string text;
  for (size_t c = 0; c < this->columns.size(); ++c)
  {
    text += (c ? "," : "") + csvCell(this->columns[c]);
  }
  text += "\n";
  for (const json& row : this->rows)
  {
    for (size_t c = 0; c < this->columns.size(); ++c)
    {
      const std::string& column = this->columns[c];
      text += (c ? "," : "") + csvCell(row.contains(column) ? row.at(column) : json());
    }
    text += "\n";
  }
  return text;
}

json CohortTable::toJson() const
{
  return { { "format", "vimlop-cohort-table" }, { "version", 1 }, { "columns", this->columns },
    { "volatile_columns", this->volatileColumns }, { "rows", this->rows } };
}

CohortTable mergeCohortTable(const CohortManifest& manifest, const CohortFolder& folder)
{
  CohortTable table;
  std::vector<std::string> figureColumns;
  std::vector<std::string> provenanceColumns;
  std::set<std::string> known;
  std::set<std::string> volatileNames;
  const auto addColumn = [&](std::vector<std::string>& group, const Figure& f)
  {
    if (known.insert(f.name).second)
    {
      group.push_back(f.name);
    }
    if (f.isVolatile)
    {
      volatileNames.insert(f.name);
    }
  };
  for (const CohortRow& row : manifest.rows)
  {
    CohortRowStatus status;
    const CohortRowState state = cohortRowState(folder, row, &status);
    const CohortRowCommand& command = *findCohortRowCommand(row.command);
    json line = { { "id", row.id }, { "command", row.commandName() } };
    std::vector<Figure> figures;
    std::vector<Figure> provenance;
    const bool hasResult = state == CohortRowState::Complete || state == CohortRowState::Flagged;
    std::string stateName = toString(state);
    if (hasResult)
    {
      const json result = readJsonFile(folder.resultPath(row));
      if (command.figures == CohortRowCommand::Figures::Registration)
      {
        figures = registrationFigures(result);
        // The result's own flag, whatever the record says (a record may be lost).
        const json* flagged = result.contains("confidence") ? &result.at("confidence") : nullptr;
        stateName = flagged && flagged->value("failure", false) ? "flagged" : "complete";
      }
      else
      {
        flatten(result, "", false, figures);
      }
      provenance = resultProvenance(result);
      fs::path output = fs::relative(folder.resultPath(row), folder.root());
      provenance.push_back({ "output", output.generic_string() });
    }
    line["state"] = stateName;
    const CohortAttempt* last = status.last();
    if (last && !last->error.empty() && !hasResult)
    {
      line["error"] = last->error;
    }
    std::vector<std::string> words = { "vimlop" };
    for (const std::string& word : row.arguments())
    {
      words.push_back(word);
    }
    provenance.push_back({ "command_line", joinCommandLine(words) });
    provenance.push_back({ "row_sha256", row.digest() });
    const bool versioned = std::any_of(provenance.begin(), provenance.end(),
      [](const Figure& f) { return f.name == "vimlop_version"; });
    if (last && !versioned && !last->vimlopVersion.empty())
    {
      provenance.push_back({ "vimlop_version", last->vimlopVersion });
    }
    if (last)
    {
      provenance.push_back({ "attempts", status.attempts.size(), true });
      provenance.push_back({ "host", last->host, true });
      provenance.push_back({ "slurm_job", last->slurmJob, true });
      provenance.push_back({ "started", last->startedUtc, true });
      provenance.push_back({ "ended", last->endedUtc, true });
      provenance.push_back({ "threads", last->threads, true });
      provenance.push_back({ "wall_s", last->wallS, true });
      provenance.push_back({ "cpu_s", last->cpuS, true });
      provenance.push_back({ "peak_resident_mib", last->peakResidentMiB, true });
    }
    for (const Figure& f : figures)
    {
      addColumn(figureColumns, f);
      line[f.name] = f.value;
    }
    for (const Figure& f : provenance)
    {
      addColumn(provenanceColumns, f);
      line[f.name] = f.value;
    }
    table.rows.push_back(std::move(line));
  }
  table.columns = { "id", "command", "state", "error" };
  for (const auto* group : { &figureColumns, &provenanceColumns })
  {
    for (const std::string& name : *group)
    {
      // A protocol's figure named like a provenance column stays one column.
      if (std::find(table.columns.begin(), table.columns.end(), name) == table.columns.end())
      {
        table.columns.push_back(name);
      }
    }
  }
  for (const std::string& name : table.columns)
  {
    if (volatileNames.count(name))
    {
      table.volatileColumns.push_back(name);
    }
  }
  return table;
}

std::string cohortRowSummary(const CohortRowCommand& command, const std::string& resultPath)
{
  if (command.figures != CohortRowCommand::Figures::Registration)
  {
    return std::string();
  }
  json result;
  try
  {
    result = readJsonFile(resultPath);
  }
  catch (const Error&)
  {
    return std::string();
  }
  std::vector<std::string> parts;
  const std::vector<Figure> figures = registrationFigures(result);
  const auto number = [&](const std::string& name, const char* format)
  {
    for (const Figure& f : figures)
    {
      if (f.name == name && f.value.is_number())
      {
        parts.push_back(formatText(format, f.value.get<double>()));
      }
    }
  };
  number("camera_position_error_mm_mean", "camera error %.3f mm");
  number("contour_error_px", "contour error %.2f px");
  std::string text;
  for (const std::string& part : parts)
  {
    text += (text.empty() ? "" : ", ") + part;
  }
  for (const Figure& f : figures)
  {
    if (f.name == "failure_reason" && f.value.is_string() && !f.value.get<std::string>().empty())
    {
      text += "; " + f.value.get<std::string>();
    }
  }
  return text;
}

} // namespace vimlop
