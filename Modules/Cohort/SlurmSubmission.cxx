#include <vimlop/Cohort/SlurmSubmission.h>

#include <vimlop/Cohort/CohortFolder.h>
#include <vimlop/Cohort/CohortManifest.h>
#include <vimlop/Cohort/CohortRowCommand.h>
#include <vimlop/Cohort/CohortRowStatus.h>
#include <vimlop/Cohort/CommandLineWords.h>
#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/ChildProcess.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <sys/stat.h>
#include <unistd.h>

namespace vimlop
{

namespace fs = std::filesystem;
using nlohmann::json;

namespace
{

/// A Slurm command's output: how it ended, its stdout and stderr.
struct CommandOutput
{
  int exitCode = -1;
  std::string out;
  std::string err;
};

std::string lastLine(std::string text)
{
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' '))
  {
    text.pop_back();
  }
  const size_t newline = text.rfind('\n');
  return newline == std::string::npos ? text : text.substr(newline + 1);
}

/// Runs a Slurm command with its outputs in files of `folder` (its stdout
/// may be long: squeue on a busy cluster).
CommandOutput runSlurmCommand(const std::vector<std::string>& arguments, const std::string& folder)
{
  fs::create_directories(folder);
  // Unique per call: several vimlop processes may ask Slurm at once.
  static std::atomic<int> calls{ 0 };
  const std::string base = folder + "/.vimlop-" + fs::path(arguments.front()).filename().string() +
    "-" + std::to_string(::getpid()) + "-" + std::to_string(++calls);
  ChildProcessOptions options;
  options.stdoutPath = base + ".out";
  options.stderrPath = base + ".err";
  CommandOutput output;
  try
  {
    output.exitCode = runChildProcess(arguments, options).exitCode;
  }
  catch (const Error& e)
  {
    throw Error(std::string(e.what()) +
      "; Slurm's commands (sbatch, squeue, scontrol) must be on PATH (Debian: slurm-client)");
  }
  output.out = readWholeFile(options.stdoutPath);
  output.err = readWholeFile(options.stderrPath);
  fs::remove(options.stdoutPath);
  fs::remove(options.stderrPath);
  return output;
}

/// Submits a batch script; returns its job id.
std::string sbatch(const std::string& program, const std::string& script, const std::string& folder)
{
  const CommandOutput output = runSlurmCommand({ program, "--parsable", script }, folder);
  std::string id = output.out.substr(0, output.out.find_first_of(";\n"));
  if (output.exitCode != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
  {
    const std::string said = lastLine(output.err.empty() ? output.out : output.err);
    throw Error("sbatch refused '" + script + "'" + (said.empty() ? "" : ": " + said));
  }
  return id;
}

/// The lines every batch script of a submission shares.
std::string commonOptions(const SlurmSubmitOptions& o)
{
  std::string lines;
  const auto line = [&](const std::string& option) { lines += "#SBATCH " + option + "\n"; };
  if (!o.partition.empty())
  {
    line("--partition=" + o.partition);
  }
  if (!o.time.empty())
  {
    line("--time=" + o.time);
  }
  if (!o.memory.empty())
  {
    line("--mem=" + o.memory);
  }
  for (const std::string& extra : o.extraArguments)
  {
    line(extra);
  }
  return lines;
}

void writeScript(const std::string& path, const std::string& text)
{
  writeFileAtomically(path, text);
  ::chmod(path.c_str(), 0755);
}

json optionsJson(const SlurmSubmitOptions& o)
{
  return { { "partition", o.partition }, { "time", o.time }, { "cpus_per_task", o.cpusPerTask },
    { "memory", o.memory }, { "rows_per_task", o.rowsPerTask }, { "max_running", o.maxRunning },
    { "extra_arguments", o.extraArguments }, { "program", o.program } };
}

SlurmSubmitOptions optionsFrom(const json& j)
{
  SlurmSubmitOptions o;
  o.partition = j.value("partition", "");
  o.time = j.value("time", "");
  o.cpusPerTask = j.value("cpus_per_task", o.cpusPerTask);
  o.memory = j.value("memory", "");
  o.rowsPerTask = j.value("rows_per_task", 0);
  o.maxRunning = j.value("max_running", 0);
  o.extraArguments = j.value("extra_arguments", std::vector<std::string>());
  o.program = j.value("program", "");
  return o;
}

/// Rows per task so that a task lasts about 20 s: Slurm's cost of about a
/// second a task is then a small share.
int defaultRowsPerTask(const CohortManifest& manifest, const std::vector<std::string>& ids)
{
  double seconds = 0.0;
  for (const std::string& id : ids)
  {
    seconds += findCohortRowCommand(manifest.find(id)->command)->typicalSeconds;
  }
  const double mean = seconds / static_cast<double>(std::max<size_t>(1, ids.size()));
  return std::max(1, static_cast<int>(std::ceil(20.0 / std::max(1.0, mean))));
}

} // namespace

SlurmPlan planSlurmTasks(const std::vector<std::string>& ids, int rowsPerTask, int maxArraySize)
{
  if (rowsPerTask < 1)
  {
    throw Error("Slurm: at least 1 row per task, not " + std::to_string(rowsPerTask));
  }
  if (maxArraySize < 1)
  {
    throw Error("Slurm: MaxArraySize must be at least 1, not " + std::to_string(maxArraySize));
  }
  SlurmPlan plan;
  for (size_t i = 0; i < ids.size(); i += static_cast<size_t>(rowsPerTask))
  {
    const size_t end = std::min(ids.size(), i + static_cast<size_t>(rowsPerTask));
    plan.tasks.emplace_back(
      ids.begin() + static_cast<std::ptrdiff_t>(i), ids.begin() + static_cast<std::ptrdiff_t>(end));
  }
  const int tasks = static_cast<int>(plan.tasks.size());
  for (int first = 0; first < tasks; first += maxArraySize)
  {
    plan.arrays.emplace_back(first, std::min(maxArraySize, tasks - first));
  }
  return plan;
}

std::vector<std::string> SlurmSubmission::jobIds() const
{
  std::vector<std::string> ids;
  for (const JobArray& array : this->arrays)
  {
    ids.push_back(array.jobId);
  }
  if (!this->mergeJobId.empty())
  {
    ids.push_back(this->mergeJobId);
  }
  return ids;
}

int slurmMaxArraySize(const std::string& scontrol)
{
  const CommandOutput output =
    runSlurmCommand({ scontrol, "show", "config" }, fs::temp_directory_path().string());
  if (output.exitCode != 0)
  {
    throw Error("scontrol show config failed: " + lastLine(output.err));
  }
  std::istringstream lines(output.out);
  std::string line;
  while (std::getline(lines, line))
  {
    if (line.compare(0, 12, "MaxArraySize") == 0)
    {
      const size_t equals = line.find('=');
      if (equals != std::string::npos)
      {
        try
        {
          return std::stoi(line.substr(equals + 1));
        }
        catch (const std::exception&)
        {
        }
      }
    }
  }
  throw Error("scontrol show config does not give MaxArraySize");
}

std::vector<std::pair<std::string, std::string>> slurmJobsInQueue(
  const std::vector<std::string>& jobIds, const std::string& squeue)
{
  std::vector<std::pair<std::string, std::string>> queued;
  if (jobIds.empty())
  {
    return queued;
  }
  // Every job (ids of finished jobs make squeue -j fail), matched here by
  // its array's job id (%F) or its own (%A).
  const CommandOutput output = runSlurmCommand(
    { squeue, "--noheader", "--format=%F|%A|%T" }, fs::temp_directory_path().string());
  if (output.exitCode != 0)
  {
    throw Error("squeue failed: " + lastLine(output.err));
  }
  std::istringstream lines(output.out);
  std::string line;
  while (std::getline(lines, line))
  {
    const size_t a = line.find('|');
    const size_t b = line.find('|', a + 1);
    if (a == std::string::npos || b == std::string::npos)
    {
      continue;
    }
    const std::string array = line.substr(0, a);
    const std::string job = line.substr(a + 1, b - a - 1);
    const std::string state = line.substr(b + 1);
    for (const std::string& id : jobIds)
    {
      const bool listed = std::any_of(queued.begin(), queued.end(),
        [&](const auto& q) { return q.first == id && q.second == state; });
      if ((id == array || id == job) && !listed)
      {
        queued.emplace_back(id, state);
      }
    }
  }
  return queued;
}

SlurmSubmission submitCohortToSlurm(const CohortManifest& manifest, const CohortFolder& folder,
  const std::vector<std::string>& ids, const SlurmSubmitOptions& options)
{
  if (ids.empty())
  {
    throw Error("nothing to submit: every row has its result or is running");
  }
  if (options.cpusPerTask < 1)
  {
    throw Error("--cpus-per-task must be at least 1, not " + std::to_string(options.cpusPerTask));
  }
  SlurmSubmission submission;
  submission.options = options;
  if (submission.options.program.empty())
  {
    submission.options.program = currentExecutablePath();
  }
  if (submission.options.rowsPerTask <= 0)
  {
    submission.options.rowsPerTask = defaultRowsPerTask(manifest, ids);
  }
  const SlurmSubmitOptions& o = submission.options;
  const int maxArraySize = slurmMaxArraySize(o.scontrol);
  const SlurmPlan plan = planSlurmTasks(ids, o.rowsPerTask, maxArraySize);
  submission.tasks = plan.tasks;
  submission.number = static_cast<int>(readSlurmSubmissions(folder).size()) + 1;
  submission.submittedUtc = utcNow();
  const std::string slurm = folder.slurmFolder();
  const std::string logs = slurm + "/logs";
  fs::create_directories(logs);
  const std::string name = "submission-" + std::to_string(submission.number);
  // The record first, without job ids: a task that starts at once finds its rows.
  const auto record = [&]
  {
    json arrays = json::array();
    for (const SlurmSubmission::JobArray& a : submission.arrays)
    {
      arrays.push_back({ { "job_id", a.jobId }, { "first_task", a.firstTask },
        { "task_count", a.taskCount }, { "script", a.script } });
    }
    const json j = { { "number", submission.number }, { "submitted", submission.submittedUtc },
      { "tasks", submission.tasks }, { "arrays", arrays },
      { "merge_job_id", submission.mergeJobId }, { "options", optionsJson(o) } };
    writeFileAtomically(slurm + "/" + name + ".json", j.dump(2) + "\n");
  };
  record();
  for (size_t k = 0; k < plan.arrays.size(); ++k)
  {
    const auto [first, count] = plan.arrays[k];
    SlurmSubmission::JobArray array;
    array.firstTask = first;
    array.taskCount = count;
    array.script = slurm + "/" + name + "-array-" + std::to_string(k + 1) + ".sbatch";
    std::string text = "#!/bin/sh\n# Written by vimlop cohort submit: one task runs the rows of "
                       "its chunk (slurm/" +
      name + ".json).\n#SBATCH --job-name=vimlop-cohort\n#SBATCH --array=0-" +
      std::to_string(count - 1) + (o.maxRunning > 0 ? "%" + std::to_string(o.maxRunning) : "") +
      "\n#SBATCH --cpus-per-task=" + std::to_string(o.cpusPerTask) + "\n#SBATCH --output=" + logs +
      "/" + name + "-array-" + std::to_string(k + 1) + "-%a.out\n" + commonOptions(o) +
      "# The task starts its own X display for the rows that render: the\n"
      "# submitting machine's display is not the node's.\nunset DISPLAY\nexec " +
      joinCommandLine({ o.program, "cohort", "task", folder.root(), "--submission",
        std::to_string(submission.number) }) +
      " --task \"$((" + std::to_string(first) + " + SLURM_ARRAY_TASK_ID))\"\n";
    writeScript(array.script, text);
    array.jobId = sbatch(o.sbatch, array.script, slurm);
    submission.arrays.push_back(array);
    record();
  }
  std::string after;
  for (const SlurmSubmission::JobArray& array : submission.arrays)
  {
    after += ":" + array.jobId;
  }
  const std::string mergeScript = slurm + "/" + name + "-merge.sbatch";
  writeScript(mergeScript,
    "#!/bin/sh\n# Written by vimlop cohort submit: the table and the report once every task "
    "ended well.\n#SBATCH --job-name=vimlop-cohort-merge\n#SBATCH --dependency=afterok" +
      after + "\n#SBATCH --kill-on-invalid-dep=yes\n#SBATCH --cpus-per-task=1\n#SBATCH --output=" +
      logs + "/" + name + "-merge.out\n" + commonOptions(o) + "exec " +
      joinCommandLine({ o.program, "cohort", "merge", folder.root() }) + "\n");
  submission.mergeJobId = sbatch(o.sbatch, mergeScript, slurm);
  record();
  return submission;
}

std::vector<SlurmSubmission> readSlurmSubmissions(const CohortFolder& folder)
{
  std::vector<SlurmSubmission> submissions;
  for (int number = 1;; ++number)
  {
    const std::string path =
      folder.slurmFolder() + "/submission-" + std::to_string(number) + ".json";
    std::ifstream in(path);
    if (!in)
    {
      break;
    }
    SlurmSubmission s;
    try
    {
      const json j = json::parse(in);
      s.number = j.at("number").get<int>();
      s.submittedUtc = j.value("submitted", "");
      s.tasks = j.at("tasks").get<std::vector<std::vector<std::string>>>();
      for (const json& a : j.at("arrays"))
      {
        s.arrays.push_back({ a.at("job_id").get<std::string>(), a.at("first_task").get<int>(),
          a.at("task_count").get<int>(), a.value("script", "") });
      }
      s.mergeJobId = j.value("merge_job_id", "");
      s.options = optionsFrom(j.value("options", json::object()));
    }
    catch (const json::exception& e)
    {
      throwFileError(path, std::string("not a Slurm submission record (") + e.what() + ")");
    }
    submissions.push_back(std::move(s));
  }
  return submissions;
}

} // namespace vimlop
