#include <vimlop/Cohort/CohortManifest.h>

#include <vimlop/Cohort/CommandLineWords.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/Sha256.h>
#include <vimlop/Core/TextFormat.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace vimlop
{

namespace fs = std::filesystem;
using nlohmann::json;

namespace
{

/// Options the cohort sets for every row, or that would never end in a batch.
const std::set<std::string>& optionsTheCohortSets()
{
  static const std::set<std::string> names = { "out", "force", "serve", "print-options" };
  return names;
}

bool safeId(const std::string& id)
{
  if (id.empty() || id.size() > 128 || id == "." || id == "..")
  {
    return false;
  }
  return std::all_of(id.begin(), id.end(),
    [](unsigned char c) { return std::isalnum(c) || c == '.' || c == '_' || c == '-'; });
}

/// Where a row came from, for messages: "'m.csv', line 4 (row 'case3')".
std::string where(const std::string& path, const CohortRow& row, bool csv)
{
  std::string text = "'" + path + "', " + (csv ? "line " : "row ") + std::to_string(row.line);
  if (!row.id.empty())
  {
    text += " ('" + row.id + "')";
  }
  return text;
}

/// A true/false text of a flag column; throws for anything else.
bool flagValue(const std::string& value, const std::string& context, const std::string& name)
{
  const std::string v = lowerCase(value);
  if (v == "true" || v == "yes" || v == "1")
  {
    return true;
  }
  if (v == "false" || v == "no" || v == "0" || v.empty())
  {
    return false;
  }
  throw Error(context + ": '" + name + "' is a flag: give true or false, not '" + value + "'");
}

/// Adds option `name` with `value` to the row, checked against the catalog.
void addOption(CohortRow& row, const std::string& name, const std::string& value,
  const CohortCommandCatalog& catalog, const std::string& context)
{
  if (name.empty())
  {
    throw Error(context + ": an option without a name");
  }
  if (optionsTheCohortSets().count(name))
  {
    throw Error(context + ": '--" + name +
      "' is the cohort's to set (each row writes its own output under the cohort folder, "
      "jobs/<id>)");
  }
  // Without a catalog, true and false make flags.
  CohortOptionKind kind =
    value == "true" || value == "false" ? CohortOptionKind::Flag : CohortOptionKind::Value;
  if (catalog.optionKind)
  {
    kind = catalog.optionKind(row.command, name);
    if (kind == CohortOptionKind::Unknown)
    {
      const std::string near = catalog.suggestion ? catalog.suggestion(row.command, name) : "";
      throw Error(context + ": '--" + name + "' is not an option of 'vimlop " + row.commandName() +
        "'" + (near.empty() ? "" : "; did you mean '--" + near + "'?"));
    }
  }
  if (kind == CohortOptionKind::Flag)
  {
    if (flagValue(value, context, name))
    {
      row.options.emplace_back(name, "");
    }
    return;
  }
  if (value.empty() && catalog.optionKind)
  {
    throw Error(context + ": '--" + name + "' needs a value");
  }
  row.options.emplace_back(name, value);
}

/// The `options` column's text or JSON array: words of a command line.
void addCommandLineOptions(CohortRow& row, const std::vector<std::string>& words,
  const CohortCommandCatalog& catalog, const std::string& context)
{
  for (size_t i = 0; i < words.size(); ++i)
  {
    const std::string& word = words[i];
    if (word.size() < 3 || word.compare(0, 2, "--") != 0)
    {
      throw Error(context + ": '" + word + "' in the options is not an option (--name)");
    }
    std::string name = word.substr(2);
    if (const size_t equals = name.find('='); equals != std::string::npos)
    {
      addOption(row, name.substr(0, equals), name.substr(equals + 1), catalog, context);
      continue;
    }
    const CohortOptionKind kind =
      catalog.optionKind ? catalog.optionKind(row.command, name) : CohortOptionKind::Unknown;
    const bool nextIsValue = i + 1 < words.size() && words[i + 1].compare(0, 2, "--") != 0;
    if (kind == CohortOptionKind::Flag || (kind == CohortOptionKind::Unknown && !nextIsValue))
    {
      addOption(row, name, "true", catalog, context);
    }
    else if (nextIsValue)
    {
      addOption(row, name, words[++i], catalog, context);
    }
    else
    {
      addOption(row, name, "", catalog, context);
    }
  }
}

/// The command's words, checked against the catalog.
std::vector<std::string> commandOf(
  const std::string& text, const CohortCommandCatalog& catalog, const std::string& context)
{
  std::vector<std::string> words = splitCommandLine(text);
  if (words.empty())
  {
    throw Error(context + ": no command (e.g. 'register' or 'evaluate synthetic')");
  }
  if (catalog.commandKnown && !catalog.commandKnown(words))
  {
    std::string joined;
    for (const std::string& w : words)
    {
      joined += (joined.empty() ? "" : " ") + w;
    }
    throw Error(context + ": 'vimlop " + joined +
      "' is not a command a cohort can run (register, or evaluate synthetic|video|"
      "perturbation|warp|budget)");
  }
  return words;
}

/// One CSV record from `in` (RFC 4180: quoted fields may hold commas,
/// doubled quotes and line breaks); false at the end of the file.
bool readCsvRecord(std::istream& in, std::vector<std::string>& fields, int& line, int& firstLine)
{
  fields.clear();
  std::string field;
  bool quoted = false;
  bool any = false;
  firstLine = line + 1;
  char c = 0;
  while (in.get(c))
  {
    any = true;
    if (quoted)
    {
      if (c == '"')
      {
        if (in.peek() == '"')
        {
          field += '"';
          in.get(c);
        }
        else
        {
          quoted = false;
        }
      }
      else
      {
        line += c == '\n';
        field += c;
      }
    }
    else if (c == '"')
    {
      quoted = true;
    }
    else if (c == ',')
    {
      fields.push_back(field);
      field.clear();
    }
    else if (c == '\n')
    {
      ++line;
      break;
    }
    else if (c != '\r')
    {
      field += c;
    }
  }
  if (quoted)
  {
    throw Error("line " + std::to_string(firstLine) + ": a quoted field is not closed");
  }
  if (!any)
  {
    return false;
  }
  fields.push_back(field);
  return true;
}

std::string trimmed(const std::string& text)
{
  const size_t begin = text.find_first_not_of(" \t");
  const size_t end = text.find_last_not_of(" \t");
  return begin == std::string::npos ? std::string() : text.substr(begin, end - begin + 1);
}

std::vector<CohortRow> readCsvRows(
  const std::string& path, std::istream& in, const CohortCommandCatalog& catalog)
{
  std::vector<std::string> header;
  std::vector<std::string> fields;
  int line = 0;
  int first = 0;
  std::vector<CohortRow> rows;
  while (true)
  {
    try
    {
      if (!readCsvRecord(in, fields, line, first))
      {
        break;
      }
    }
    catch (const Error& e)
    {
      throw Error("'" + path + "', " + e.what());
    }
    const std::string start = fields.empty() ? "" : trimmed(fields.front());
    const bool blank = std::all_of(
      fields.begin(), fields.end(), [](const std::string& f) { return trimmed(f).empty(); });
    if (blank || (!start.empty() && start.front() == '#'))
    {
      continue;
    }
    if (header.empty())
    {
      for (const std::string& f : fields)
      {
        header.push_back(trimmed(f));
      }
      for (const char* needed : { "id", "command" })
      {
        if (std::find(header.begin(), header.end(), needed) == header.end())
        {
          throw Error("'" + path + "', line " + std::to_string(first) +
            ": the header has no column '" + needed + "' (a manifest needs id and command)");
        }
      }
      std::set<std::string> seen;
      for (const std::string& h : header)
      {
        if (h.empty() || !seen.insert(h).second)
        {
          throw Error("'" + path + "', line " + std::to_string(first) +
            (h.empty() ? ": a column without a name" : ": the column '" + h + "' is repeated"));
        }
      }
      continue;
    }
    CohortRow row;
    row.line = first;
    for (size_t i = 0; i < std::min(header.size(), fields.size()); ++i)
    {
      if (header[i] == "id")
      {
        row.id = trimmed(fields[i]);
      }
    }
    if (fields.size() != header.size())
    {
      throw Error(where(path, row, true) + ": " + std::to_string(fields.size()) +
        " fields where the header has " + std::to_string(header.size()));
    }
    const std::string context = where(path, row, true);
    for (size_t i = 0; i < header.size(); ++i)
    {
      if (header[i] == "command")
      {
        row.command = commandOf(fields[i], catalog, context);
      }
    }
    for (size_t i = 0; i < header.size(); ++i)
    {
      const std::string value = trimmed(fields[i]);
      if (header[i] == "options")
      {
        addCommandLineOptions(row, splitCommandLine(value), catalog, context);
      }
      else if (header[i] != "id" && header[i] != "command" && !value.empty())
      {
        // An empty cell leaves the option out: rows of other commands share the columns.
        addOption(row, header[i], value, catalog, context);
      }
    }
    rows.push_back(std::move(row));
  }
  if (header.empty())
  {
    throwFileError(path, "no header line (a manifest needs the columns id and command)");
  }
  return rows;
}

/// A JSON value of a row as the text of an option: numbers as written
/// (whole numbers without a decimal point), true/false for flags.
std::string jsonOptionText(const json& value, const std::string& context, const std::string& name)
{
  if (value.is_string())
  {
    return value.get<std::string>();
  }
  if (value.is_boolean())
  {
    return value.get<bool>() ? "true" : "false";
  }
  if (value.is_number_integer() || value.is_number_unsigned())
  {
    return value.dump();
  }
  if (value.is_number_float() && std::isfinite(value.get<double>()))
  {
    return value.dump();
  }
  throw Error(context + ": '" + name + "' must be a string, a number or true/false");
}

std::vector<CohortRow> readJsonRows(
  const std::string& path, std::istream& in, const CohortCommandCatalog& catalog)
{
  json manifest;
  try
  {
    in >> manifest;
  }
  catch (const json::exception& e)
  {
    throwFileError(path, std::string("not valid JSON (") + e.what() + ")");
  }
  if (!manifest.is_object() || !manifest.contains("rows") || !manifest.at("rows").is_array())
  {
    throwFileError(path, "a JSON manifest is an object with an array \"rows\"");
  }
  std::vector<CohortRow> rows;
  int position = 0;
  for (const json& entry : manifest.at("rows"))
  {
    CohortRow row;
    row.line = ++position;
    if (!entry.is_object())
    {
      throw Error(where(path, row, false) + ": a row is an object");
    }
    if (entry.contains("id") && entry.at("id").is_string())
    {
      row.id = entry.at("id").get<std::string>();
    }
    const std::string context = where(path, row, false);
    if (!entry.contains("command") || !entry.at("command").is_string())
    {
      throw Error(context + ": no command (e.g. \"register\" or \"evaluate synthetic\")");
    }
    row.command = commandOf(entry.at("command").get<std::string>(), catalog, context);
    for (const auto& [name, value] : entry.items())
    {
      if (name == "id" || name == "command")
      {
        continue;
      }
      if (name != "options")
      {
        addOption(row, name, jsonOptionText(value, context, name), catalog, context);
      }
      else if (value.is_object())
      {
        for (const auto& [option, text] : value.items())
        {
          addOption(row, option, jsonOptionText(text, context, option), catalog, context);
        }
      }
      else if (value.is_array())
      {
        std::vector<std::string> words;
        for (const json& word : value)
        {
          words.push_back(jsonOptionText(word, context, "options"));
        }
        addCommandLineOptions(row, words, catalog, context);
      }
      else
      {
        throw Error(context + ": \"options\" is an object {name: value} or an array of words");
      }
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

} // namespace

std::string CohortRow::commandName() const
{
  std::string name;
  for (const std::string& word : this->command)
  {
    name += (name.empty() ? "" : " ") + word;
  }
  return name;
}

std::vector<std::string> CohortRow::arguments() const
{
  std::vector<std::string> words = this->command;
  for (const auto& [name, value] : this->options)
  {
    words.push_back("--" + name);
    if (!value.empty())
    {
      words.push_back(value);
    }
  }
  return words;
}

std::string CohortRow::digest() const
{
  // Each word with its length, so that no two argument lists share a text.
  Sha256 sha;
  for (const std::string& word : this->arguments())
  {
    sha.update(std::to_string(word.size()) + ":" + word + "\n");
  }
  return sha.hex();
}

const CohortRow* CohortManifest::find(const std::string& id) const
{
  for (const CohortRow& row : this->rows)
  {
    if (row.id == id)
    {
      return &row;
    }
  }
  return nullptr;
}

CohortManifest readCohortManifest(const std::string& path, const CohortCommandCatalog& catalog)
{
  std::error_code error;
  if (!fs::is_regular_file(path, error))
  {
    throwFileError(path, fs::exists(path, error) ? "not a file" : "no such file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throwFileError(path, "cannot read it");
  }
  const std::string extension = lowerCaseExtension(path);
  CohortManifest manifest;
  manifest.path = fs::absolute(path).lexically_normal().string();
  manifest.folder = fs::path(manifest.path).parent_path().string();
  if (extension == ".csv")
  {
    manifest.rows = readCsvRows(path, in, catalog);
  }
  else if (extension == ".json")
  {
    manifest.rows = readJsonRows(path, in, catalog);
  }
  else
  {
    throwFileError(path, "a manifest is a .csv or .json file");
  }
  std::set<std::string> ids;
  const bool csv = extension == ".csv";
  for (const CohortRow& row : manifest.rows)
  {
    if (row.id.empty())
    {
      throw Error(where(path, row, csv) + ": no id");
    }
    if (!safeId(row.id))
    {
      throw Error(where(path, row, csv) +
        ": an id is its output's folder name: letters, digits, '.', '_' and '-' only");
    }
    if (!ids.insert(row.id).second)
    {
      throw Error(where(path, row, csv) + ": the id is used by an earlier row");
    }
  }
  if (manifest.rows.empty())
  {
    throwFileError(path, "no rows");
  }
  return manifest;
}

} // namespace vimlop
