#include "CommandLine.h"
#include "Commands.h"
#include <vimlop/Cohort/CohortFolder.h>
#include <vimlop/Cohort/CohortManifest.h>
#include <vimlop/Cohort/CohortReportPage.h>
#include <vimlop/Cohort/CohortRowCommand.h>
#include <vimlop/Cohort/CohortRunner.h>
#include <vimlop/Cohort/CohortTable.h>
#include <vimlop/Cohort/SlurmSubmission.h>
#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

#include <CLI/CLI.hpp>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

namespace vimlop
{

namespace
{

namespace fs = std::filesystem;

/// The program's own commands and options, for checking a manifest's rows.
CohortCommandCatalog catalogOf(const CLI::App& root)
{
  const auto commandOf = [&root](const std::vector<std::string>& words) -> const CLI::App*
  {
    if (!findCohortRowCommand(words))
    {
      return nullptr;
    }
    const CLI::App* app = &root;
    for (const std::string& word : words)
    {
      const std::vector<const CLI::App*> children =
        app->get_subcommands([&](const CLI::App* c) { return c->get_name() == word; });
      if (children.empty())
      {
        return nullptr;
      }
      app = children.front();
    }
    return app;
  };
  CohortCommandCatalog catalog;
  catalog.commandKnown = [commandOf](const std::vector<std::string>& words)
  { return commandOf(words) != nullptr; };
  catalog.optionKind = [commandOf](const std::vector<std::string>& words, const std::string& name)
  {
    const CLI::App* app = commandOf(words);
    const CLI::Option* option = app ? app->get_option_no_throw("--" + name) : nullptr;
    if (!option)
    {
      return CohortOptionKind::Unknown;
    }
    return option->get_expected_min() == 0 ? CohortOptionKind::Flag : CohortOptionKind::Value;
  };
  catalog.suggestion = [commandOf](const std::vector<std::string>& words, const std::string& name)
  {
    std::vector<std::string> names;
    if (const CLI::App* app = commandOf(words))
    {
      for (const CLI::Option* option : app->get_options())
      {
        for (const std::string& longName : option->get_lnames())
        {
          names.push_back(longName);
        }
      }
    }
    return nearestName(name, names);
  };
  return catalog;
}

/// "1 row", "3 rows".
std::string counted(size_t count, const char* noun)
{
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

/// One line per finished row, as `cohort run` and a Slurm task print them
/// (to stdout, or to stderr when stdout is for the JSON summary).
void printOutcome(std::ostream& out, const CohortRowOutcome& o, int done, int total)
{
  std::string line = formatText("cohort: [%d/%d] %s: ", done, total, o.id.c_str());
  if (o.state == CohortRowState::Running)
  {
    line += "left alone: another run holds it";
  }
  else
  {
    line += std::string(toString(o.state)) + formatText(" in %.1f s", o.attempt.wallS);
    if (o.state == CohortRowState::Failed || o.state == CohortRowState::Interrupted)
    {
      line += ": " + o.attempt.error;
    }
    else if (!o.summary.empty())
    {
      line += " (" + o.summary + ")";
    }
  }
  out << line << std::endl;
}

/// Runs rows with the terminal's progress and Ctrl-C; returns the exit code:
/// 0 when every selected row has its result, 3 when some have none.
int runRows(
  const CohortManifest& manifest, const CohortFolder& folder, CohortRunOptions options, bool json)
{
  const InterruptGuard guard;
  std::ostream& progress = json ? std::cerr : std::cout;
  options.keepGoing = [] { return !InterruptGuard::requested(); };
  options.onRowDone = [&progress](const CohortRowOutcome& o, int done, int total)
  { printOutcome(progress, o, done, total); };
  options.onNote = [&progress](const std::string& note)
  { progress << "cohort: " << note << std::endl; };
  const CohortRunReport report = runCohort(manifest, folder, options);
  const int failed = report.count(CohortRowState::Failed);
  CommandSummary summary;
  summary.lines.push_back(formatText("cohort: %s: %d complete before, %d ran now (%d complete, %d "
                                     "flagged, %d failed, %d interrupted)",
    counted(report.selected, "row").c_str(), report.alreadyComplete,
    static_cast<int>(report.outcomes.size()), report.count(CohortRowState::Complete),
    report.count(CohortRowState::Flagged), failed, report.count(CohortRowState::Interrupted)));
  summary.json = { { "selected", report.selected }, { "complete_before", report.alreadyComplete },
    { "ran", report.outcomes.size() }, { "complete", report.count(CohortRowState::Complete) },
    { "flagged", report.count(CohortRowState::Flagged) }, { "failed", failed },
    { "interrupted", report.count(CohortRowState::Interrupted) },
    { "failures", nlohmann::json::array() } };
  for (const CohortRowOutcome& o : report.outcomes)
  {
    if (o.state == CohortRowState::Failed)
    {
      summary.lines.push_back("cohort: failed: " + o.id + ": " + o.attempt.error +
        " (log: " + folder.logPath(o.id) + ")");
      summary.json["failures"].push_back(
        { { "id", o.id }, { "error", o.attempt.error }, { "log", folder.logPath(o.id) } });
    }
  }
  printSummary(summary, json);
  if (report.interrupted)
  {
    std::cerr << "vimlop: interrupted; run the same command again to finish the cohort\n";
    return 130;
  }
  return failed > 0 || report.count(CohortRowState::Interrupted) > 0 ? 3 : 0;
}

/// The Slurm flags of submit and resubmit.
struct SlurmFlags
{
  SlurmSubmitOptions options;
  bool slurm = false;
  std::vector<std::string> extra;
};

void addSlurmFlags(CLI::App& command, SlurmFlags& f)
{
  SlurmSubmitOptions& o = f.options;
  command.add_option("--partition", o.partition, "Slurm partition (default: the cluster's)");
  command.add_option("--time", o.time, "time limit of each array task, e.g. 2:00:00");
  command.add_option("--cpus-per-task", o.cpusPerTask, "cores of each task (its rows' threads)")
    ->capture_default_str()
    ->check(CLI::Range(1, 1024));
  command.add_option("--mem", o.memory, "memory of each task, e.g. 8G (default: the cluster's)");
  command
    .add_option("--array-chunk", o.rowsPerTask,
      "rows per array task (default: enough for a task to last about 20 s)")
    ->check(CLI::Range(1, 1000000));
  command.add_option("--max-running", o.maxRunning, "at most this many tasks at once (%N)")
    ->check(CLI::Range(1, 1000000));
  command.add_option("--sbatch-option", f.extra,
    "another sbatch option, as one word (repeatable), e.g. --sbatch-option=--account=lab");
}

/// Refuses a new submission while earlier jobs of the cohort are queued or running.
void requireNoJobsInQueue(const CohortFolder& folder, const std::string& squeue)
{
  std::vector<std::string> ids;
  for (const SlurmSubmission& s : readSlurmSubmissions(folder))
  {
    for (const std::string& id : s.jobIds())
    {
      ids.push_back(id);
    }
  }
  const auto queued = slurmJobsInQueue(ids, squeue);
  if (!queued.empty())
  {
    std::string list;
    for (const auto& [id, state] : queued)
    {
      list += (list.empty() ? "" : ", ") + id + " (" + state + ")";
    }
    throw Error("the cohort's Slurm jobs " + list +
      " are still queued or running: wait for them (vimlop cohort status) or scancel them");
  }
}

/// The rows to submit: those without a result that do not run now (with
/// `onlyFailed`, only those that failed or were interrupted).
std::vector<std::string> rowsToSubmit(
  const CohortManifest& manifest, const CohortFolder& folder, bool onlyFailed)
{
  std::vector<std::string> ids;
  for (const CohortRow& row : manifest.rows)
  {
    const CohortRowState state = cohortRowState(folder, row);
    const bool failed = state == CohortRowState::Failed || state == CohortRowState::Interrupted;
    const bool open = state != CohortRowState::Complete && state != CohortRowState::Flagged &&
      state != CohortRowState::Running;
    if (onlyFailed ? failed : open)
    {
      ids.push_back(row.id);
    }
  }
  return ids;
}

void submit(const CohortManifest& manifest, const CohortFolder& folder,
  const std::vector<std::string>& ids, const SlurmSubmitOptions& options, bool json)
{
  const SlurmSubmission s = submitCohortToSlurm(manifest, folder, ids, options);
  std::string arrays;
  for (const SlurmSubmission::JobArray& a : s.arrays)
  {
    arrays += (arrays.empty() ? "" : ", ") + a.jobId + " (" + counted(a.taskCount, "task") + ")";
  }
  CommandSummary summary;
  summary.lines.push_back(
    formatText("cohort: submission %d: %s in %s of at most %s: job %s %s; merge job %s (after "
               "every task ends well)",
      s.number, counted(ids.size(), "row").c_str(), counted(s.tasks.size(), "task").c_str(),
      counted(s.options.rowsPerTask, "row").c_str(), s.arrays.size() == 1 ? "array" : "arrays",
      arrays.c_str(), s.mergeJobId.c_str()));
  summary.lines.push_back("cohort: follow it with 'vimlop cohort status " + folder.root() + "'");
  summary.json = { { "submission", s.number }, { "rows", ids }, { "tasks", s.tasks.size() },
    { "rows_per_task", s.options.rowsPerTask }, { "job_arrays", nlohmann::json::array() },
    { "merge_job", s.mergeJobId }, { "folder", folder.root() } };
  for (const SlurmSubmission::JobArray& a : s.arrays)
  {
    summary.json["job_arrays"].push_back({ { "job", a.jobId }, { "tasks", a.taskCount } });
  }
  printSummary(summary, json);
}

/// `vimlop cohort status`: every row's state, the failures, the Slurm jobs.
void printStatus(const CohortManifest& manifest, const CohortFolder& folder, bool json)
{
  std::map<std::string, int> counts;
  nlohmann::json rows = nlohmann::json::array();
  std::vector<std::string> problems;
  for (const CohortRow& row : manifest.rows)
  {
    CohortRowStatus status;
    const CohortRowState state = cohortRowState(folder, row, &status);
    ++counts[toString(state)];
    const CohortAttempt* last = status.last();
    nlohmann::json entry = { { "id", row.id }, { "state", toString(state) },
      { "attempts", status.attempts.size() } };
    if (last)
    {
      entry["host"] = last->host;
      entry["slurm_job"] = last->slurmJob;
      entry["error"] = last->error;
    }
    rows.push_back(entry);
    if (state == CohortRowState::Failed || state == CohortRowState::Interrupted ||
      state == CohortRowState::Changed)
    {
      problems.push_back(
        formatText("cohort: %s %s (attempt %zu%s%s)%s", toString(state), row.id.c_str(),
          status.attempts.size(), last && !last->host.empty() ? (" on " + last->host).c_str() : "",
          last && !last->slurmJob.empty() ? (", Slurm " + last->slurmJob).c_str() : "",
          last && !last->error.empty() ? (": " + last->error).c_str() : ""));
    }
  }
  nlohmann::json jobs = nlohmann::json::array();
  const std::vector<SlurmSubmission> submissions = readSlurmSubmissions(folder);
  std::vector<std::pair<std::string, std::string>> queued;
  std::string squeueProblem;
  if (!submissions.empty())
  {
    std::vector<std::string> ids;
    for (const SlurmSubmission& s : submissions)
    {
      for (const std::string& id : s.jobIds())
      {
        ids.push_back(id);
      }
    }
    try
    {
      queued = slurmJobsInQueue(ids);
    }
    catch (const Error& e)
    {
      squeueProblem = e.what();
    }
    for (const auto& [id, state] : queued)
    {
      jobs.push_back({ { "job_id", id }, { "state", state } });
    }
  }
  if (json)
  {
    nlohmann::json j = { { "manifest", manifest.path }, { "rows", rows }, { "counts", counts },
      { "submissions", submissions.size() }, { "jobs_in_queue", jobs } };
    std::cout << j.dump(2) << std::endl;
    return;
  }
  std::string line;
  for (const auto& [state, count] : counts)
  {
    line += (line.empty() ? "" : ", ") + std::to_string(count) + " " + state;
  }
  std::cout << "cohort '" << folder.root() << "' of '" << manifest.path
            << "': " << counted(manifest.rows.size(), "row") << ": " << line << std::endl;
  for (const std::string& problem : problems)
  {
    std::cout << problem << std::endl;
  }
  for (const SlurmSubmission& s : submissions)
  {
    std::cout << formatText("cohort: Slurm submission %d (%s): %s", s.number,
      s.submittedUtc.c_str(), counted(s.tasks.size(), "task").c_str());
    for (const std::string& id : s.jobIds())
    {
      std::string state = "ended";
      for (const auto& [queuedId, queuedState] : queued)
      {
        state = queuedId == id ? queuedState : state;
      }
      std::cout << "; job " << id << (id == s.mergeJobId ? " (merge)" : "") << " "
                << (squeueProblem.empty() ? state : "?");
    }
    std::cout << std::endl;
  }
  if (!squeueProblem.empty())
  {
    std::cout << "cohort: cannot ask Slurm about the jobs: " << squeueProblem << std::endl;
  }
}

void merge(const CohortManifest& manifest, const CohortFolder& folder, bool json)
{
  const CohortTable table = mergeCohortTable(manifest, folder);
  writeFileAtomically(folder.tableCsvPath(), table.csv());
  writeFileAtomically(folder.tableJsonPath(), table.toJson().dump(2) + "\n");
  writeCohortReportPage(table, fs::path(manifest.path).filename().string(), folder.reportFolder());
  const auto without = table.rowsIn({ "failed", "interrupted", "changed", "not run", "running" });
  CommandSummary summary;
  summary.lines.push_back(
    formatText("cohort: merged %s (%zu without a result) into '%s', '%s' and '%s/index.html'",
      counted(table.rows.size(), "row").c_str(), without.size(), folder.tableCsvPath().c_str(),
      folder.tableJsonPath().c_str(), folder.reportFolder().c_str()));
  summary.json = { { "rows", table.rows.size() }, { "without_result", nlohmann::json::array() },
    { "table_csv", folder.tableCsvPath() }, { "table_json", folder.tableJsonPath() },
    { "report", folder.reportFolder() + "/index.html" } };
  for (const nlohmann::json* row : without)
  {
    summary.lines.push_back("cohort: " + row->value("state", "") + ": " + row->value("id", "") +
      (row->contains("error") ? ": " + row->at("error").get<std::string>() : ""));
    summary.json["without_result"].push_back(*row);
  }
  printSummary(summary, json);
}

} // namespace

void addCohortCommand(CLI::App& app)
{
  CLI::App* cohort = app.add_subcommand("cohort",
    "Many registrations and protocol runs as one study: a manifest of rows run on this machine "
    "(run) or as Slurm job arrays (submit), resumable, merged into one table and report");
  cohort->require_subcommand(1);
  const CLI::App* root = &app;

  struct RunFlags
  {
    std::string manifest, out;
    CohortRunOptions options;
    std::string rows;
    bool json = false;
  };
  auto r = std::make_shared<RunFlags>();
  CLI::App* run = cohort->add_subcommand("run",
    "Run a manifest's rows on this machine, N at a time, skipping rows already complete (an "
    "interrupted run resumes); exit code 3 when a row has no result");
  run->add_option("manifest", r->manifest, "the manifest (.csv or .json)")->required();
  run->add_option("--out", r->out, "the cohort folder")->required();
  run->add_option("--jobs", r->options.jobs, "rows at once, each its own process")
    ->capture_default_str()
    ->check(CLI::Range(1, 1024));
  run
    ->add_option("--threads-per-job", r->options.threadsPerJob,
      "threads of each row (0: the cores shared among the jobs)")
    ->capture_default_str()
    ->check(CLI::Range(0, 1024));
  run->add_option("--rows", r->rows, "only these rows: ids separated by commas");
  run->add_flag(
    "--failed", r->options.onlyFailed, "only rows that failed or were interrupted before");
  addJsonFlag(*run, r->json);
  run->callback(
    [r, root]
    {
      const CohortManifest manifest = readCohortManifest(r->manifest, catalogOf(*root));
      const CohortFolder folder(r->out);
      folder.prepare(manifest);
      if (!r->rows.empty())
      {
        r->options.rows = parseList(r->rows, "--rows");
      }
      const int code = runRows(manifest, folder, r->options, r->json);
      if (code != 0)
      {
        throw ExitRequest{ code };
      }
    });

  struct SubmitFlags
  {
    std::string manifest, out;
    SlurmFlags slurm;
    bool json = false;
  };
  auto s = std::make_shared<SubmitFlags>();
  CLI::App* submitCommand = cohort->add_subcommand("submit",
    "Submit a manifest's rows without a result as Slurm job arrays, with a merge job after them");
  submitCommand->add_option("manifest", s->manifest, "the manifest (.csv or .json)")->required();
  submitCommand->add_option("--out", s->out, "the cohort folder (on a shared file system)")
    ->required();
  submitCommand->add_flag("--slurm", s->slurm.slurm, "submit to Slurm (sbatch)")->required();
  addSlurmFlags(*submitCommand, s->slurm);
  addJsonFlag(*submitCommand, s->json);
  submitCommand->callback(
    [s, root]
    {
      const CohortManifest manifest = readCohortManifest(s->manifest, catalogOf(*root));
      const CohortFolder folder(s->out);
      folder.prepare(manifest);
      requireNoJobsInQueue(folder, s->slurm.options.squeue);
      s->slurm.options.extraArguments = s->slurm.extra;
      submit(manifest, folder, rowsToSubmit(manifest, folder, false), s->slurm.options, s->json);
    });

  struct ResubmitFlags
  {
    std::string folder;
    bool failed = false;
    SlurmFlags slurm;
    bool json = false;
  };
  auto u = std::make_shared<ResubmitFlags>();
  CLI::App* resubmit = cohort->add_subcommand("resubmit",
    "Submit a cohort's rows again to Slurm: with --failed only those that failed or were "
    "interrupted (after a fix: the manifest is read again), else every row without a result; "
    "the last submission's settings unless given");
  resubmit->add_option("folder", u->folder, "the cohort folder")->required();
  resubmit->add_flag("--failed", u->failed, "only rows that failed or were interrupted");
  addJsonFlag(*resubmit, u->json);
  addSlurmFlags(*resubmit, u->slurm);
  resubmit->callback(
    [u, root, resubmit]
    {
      const CohortFolder folder(u->folder);
      CohortManifest manifest = folder.manifest(catalogOf(*root));
      // The user's fix may be in the manifest itself: read it again where it is.
      if (fs::exists(manifest.path))
      {
        manifest = readCohortManifest(manifest.path, catalogOf(*root));
        folder.prepare(manifest);
      }
      const std::vector<SlurmSubmission> earlier = readSlurmSubmissions(folder);
      SlurmSubmitOptions o = earlier.empty() ? u->slurm.options : earlier.back().options;
      const SlurmSubmitOptions& given = u->slurm.options;
      const auto set = [&](const char* flag) { return resubmit->count(flag) > 0; };
      o.partition = set("--partition") ? given.partition : o.partition;
      o.time = set("--time") ? given.time : o.time;
      o.cpusPerTask = set("--cpus-per-task") ? given.cpusPerTask : o.cpusPerTask;
      o.memory = set("--mem") ? given.memory : o.memory;
      o.rowsPerTask = set("--array-chunk") ? given.rowsPerTask : 0;
      o.maxRunning = set("--max-running") ? given.maxRunning : o.maxRunning;
      o.extraArguments = set("--sbatch-option") ? u->slurm.extra : o.extraArguments;
      o.program.clear(); // the program resubmitting, which may be a newer one
      requireNoJobsInQueue(folder, o.squeue);
      const std::vector<std::string> ids = rowsToSubmit(manifest, folder, u->failed);
      if (ids.empty())
      {
        const std::string reason =
          u->failed ? "no row failed or was interrupted" : "every row has its result or is running";
        printSummary({ { "cohort: nothing to resubmit: " + reason },
                       { { "submission", nullptr }, { "reason", reason } } },
          u->json);
        return;
      }
      submit(manifest, folder, ids, o, u->json);
    });

  auto statusFolder = std::make_shared<std::string>();
  auto statusJson = std::make_shared<bool>(false);
  CLI::App* status = cohort->add_subcommand(
    "status", "Where each row of a cohort stands, its failures and its Slurm jobs");
  status->add_option("folder", *statusFolder, "the cohort folder")->required();
  addJsonFlag(*status, *statusJson);
  status->callback(
    [statusFolder, statusJson, root]
    {
      const CohortFolder folder(*statusFolder);
      printStatus(folder.manifest(catalogOf(*root)), folder, *statusJson);
    });

  auto mergeFolder = std::make_shared<std::string>();
  auto mergeJson = std::make_shared<bool>(false);
  CLI::App* mergeCommand = cohort->add_subcommand("merge",
    "One table of every row's figures and provenance (table.csv, table.json) and the cohort's "
    "report page (report/index.html)");
  mergeCommand->add_option("folder", *mergeFolder, "the cohort folder")->required();
  addJsonFlag(*mergeCommand, *mergeJson);
  mergeCommand->callback(
    [mergeFolder, mergeJson, root]
    {
      const CohortFolder folder(*mergeFolder);
      merge(folder.manifest(catalogOf(*root)), folder, *mergeJson);
    });

  struct TaskFlags
  {
    std::string folder;
    int submission = 0;
    int task = -1;
  };
  auto t = std::make_shared<TaskFlags>();
  CLI::App* task = cohort->add_subcommand("task",
    "Run the rows of one task of a Slurm submission (what each array task of `cohort submit` "
    "runs); a row that fails is recorded, and the task still ends well");
  task->add_option("folder", t->folder, "the cohort folder")->required();
  task->add_option("--submission", t->submission, "the submission's number")
    ->required()
    ->check(CLI::Range(1, 1000000));
  task->add_option("--task", t->task, "the task's index in the submission")
    ->required()
    ->check(CLI::Range(0, 100000000));
  task->callback(
    [t, root]
    {
      const CohortFolder folder(t->folder);
      const CohortManifest manifest = folder.manifest(catalogOf(*root));
      const std::vector<SlurmSubmission> submissions = readSlurmSubmissions(folder);
      if (t->submission > static_cast<int>(submissions.size()))
      {
        throw Error(
          "'" + folder.root() + "' has no Slurm submission " + std::to_string(t->submission));
      }
      const SlurmSubmission& s = submissions[static_cast<size_t>(t->submission - 1)];
      if (t->task >= static_cast<int>(s.tasks.size()))
      {
        throw Error("Slurm submission " + std::to_string(t->submission) + " has " +
          std::to_string(s.tasks.size()) + " tasks, not a task " + std::to_string(t->task));
      }
      CohortRunOptions options;
      options.rows = s.tasks[static_cast<size_t>(t->task)];
      options.threadsPerJob = s.options.cpusPerTask;
      const char* job = std::getenv("SLURM_ARRAY_JOB_ID");
      const char* index = std::getenv("SLURM_ARRAY_TASK_ID");
      options.slurmJob = job && index ? std::string(job) + "_" + index : std::string();
      // A row without a result is in its record; the task itself ended well.
      runRows(manifest, folder, options, false);
    });
}

} // namespace vimlop
