#include <vimlop/Cohort/CohortFolder.h>

#include <vimlop/Cohort/CohortManifest.h>
#include <vimlop/Cohort/CohortRowCommand.h>
#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>

#include <nlohmann/json.hpp>

#include <filesystem>

namespace vimlop
{

namespace fs = std::filesystem;
using nlohmann::json;

namespace
{

const char* const formatName = "vimlop-cohort";

/// cohort.json of a cohort folder, or a null JSON when there is none.
json readRecord(const std::string& path)
{
  if (!fs::exists(path))
  {
    return json();
  }
  try
  {
    json record = json::parse(readWholeFile(path));
    if (record.is_object() && record.value("format", "") == formatName &&
      record.contains("manifest") && record.at("manifest").is_string() &&
      record.contains("folder") && record.at("folder").is_string())
    {
      return record;
    }
  }
  catch (const json::exception&)
  {
  }
  throwFileError(path, "not a VIMLOP cohort record");
}

} // namespace

CohortFolder::CohortFolder(const std::string& root)
  : Root(fs::absolute(root).lexically_normal().string())
{
  while (this->Root.size() > 1 && this->Root.back() == '/')
  {
    this->Root.pop_back();
  }
}

std::string CohortFolder::rowFolder(const std::string& id) const
{
  return this->Root + "/jobs/" + id;
}

std::string CohortFolder::resultPath(const CohortRow& row) const
{
  const CohortRowCommand* command = findCohortRowCommand(row.command);
  if (!command)
  {
    throw Error("'vimlop " + row.commandName() + "' is not a command a cohort can run");
  }
  return this->rowFolder(row.id) + "/" + command->resultFile;
}

std::string CohortFolder::outArgument(const CohortRow& row) const
{
  const CohortRowCommand* command = findCohortRowCommand(row.command);
  if (command && command->output == CohortRowCommand::Output::Folder)
  {
    return this->rowFolder(row.id);
  }
  return this->resultPath(row);
}

std::string CohortFolder::statusPath(const std::string& id) const
{
  return this->Root + "/status/" + id + ".json";
}

std::string CohortFolder::lockPath(const std::string& id) const
{
  return this->Root + "/status/" + id + ".lock";
}

std::string CohortFolder::logPath(const std::string& id) const
{
  return this->Root + "/logs/" + id + ".log";
}

std::string CohortFolder::recordPath() const
{
  return this->Root + "/cohort.json";
}

std::string CohortFolder::manifestCopyPath(const std::string& manifestPath) const
{
  return this->Root + "/manifest" + lowerCaseExtension(manifestPath);
}

std::string CohortFolder::slurmFolder() const
{
  return this->Root + "/slurm";
}

std::string CohortFolder::tableCsvPath() const
{
  return this->Root + "/table.csv";
}

std::string CohortFolder::tableJsonPath() const
{
  return this->Root + "/table.json";
}

std::string CohortFolder::reportFolder() const
{
  return this->Root + "/report";
}

void CohortFolder::prepare(const CohortManifest& manifest) const
{
  std::error_code error;
  if (fs::exists(this->Root, error) && !fs::is_directory(this->Root, error))
  {
    throwFileError(this->Root, "not a folder (a cohort folder is expected)");
  }
  const json record = readRecord(this->recordPath());
  if (record.is_null() && fs::is_directory(this->Root, error) && !fs::is_empty(this->Root, error))
  {
    throw Error(
      "'" + this->Root + "': a folder with other files, not a cohort folder; choose another --out");
  }
  if (!record.is_null() && record.at("manifest").get<std::string>() != manifest.path)
  {
    throw Error("'" + this->Root + "' holds the cohort of '" +
      record.at("manifest").get<std::string>() + "', not of '" + manifest.path +
      "'; choose another --out");
  }
  for (const char* part : { "jobs", "status", "logs" })
  {
    fs::create_directories(this->Root + "/" + part, error);
    if (error)
    {
      throw Error(
        "'" + this->Root + "/" + part + "': cannot make the folder (" + error.message() + ")");
    }
  }
  const json updated = { { "format", formatName }, { "version", 1 }, { "manifest", manifest.path },
    { "folder", manifest.folder }, { "vimlop_version", VIMLOP_VERSION } };
  if (updated != record)
  {
    writeFileAtomically(this->recordPath(), updated.dump(2) + "\n");
  }
  writeFileAtomically(this->manifestCopyPath(manifest.path), readWholeFile(manifest.path));
}

CohortManifest CohortFolder::manifest(const CohortCommandCatalog& catalog) const
{
  const json record = readRecord(this->recordPath());
  if (record.is_null())
  {
    throwFileError(this->Root, "not a cohort folder (no cohort.json)");
  }
  const std::string original = record.at("manifest").get<std::string>();
  CohortManifest manifest = readCohortManifest(this->manifestCopyPath(original), catalog);
  manifest.path = original;
  manifest.folder = record.at("folder").get<std::string>();
  return manifest;
}

} // namespace vimlop
