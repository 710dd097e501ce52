#ifndef vimlop_SlurmSubmission_h
#define vimlop_SlurmSubmission_h

#include <string>
#include <utility>
#include <vector>

namespace vimlop
{

class CohortFolder;
struct CohortManifest;

/**
 * @brief Rows chunked into the tasks of Slurm job arrays: `tasks` lists each
 * task's rows (ids, in the manifest's order); `arrays` each job array's
 * first task and task count, at most the cluster's MaxArraySize each (a
 * cohort with more tasks is split into several arrays).
 */
struct SlurmPlan
{
  std::vector<std::vector<std::string>> tasks;
  std::vector<std::pair<int, int>> arrays;
};

/**
 * @brief Chunks `ids` into tasks of `rowsPerTask` rows (the last may have
 * fewer) and the tasks into arrays of at most `maxArraySize` tasks.
 * @throws vimlop::Error when `rowsPerTask` or `maxArraySize` is below 1.
 */
SlurmPlan planSlurmTasks(const std::vector<std::string>& ids, int rowsPerTask, int maxArraySize);

/// @brief How `vimlop cohort submit --slurm` asks Slurm for the cohort's tasks.
struct SlurmSubmitOptions
{
  /// --partition; empty: the cluster's default partition.
  std::string partition;
  /// --time of each task, in Slurm's format ("2:00:00"); empty: the partition's default.
  std::string time;
  /// --cpus-per-task; each row's command gets as many threads. Default 2.
  int cpusPerTask = 2;
  /// --mem of each task ("8G"); empty: the cluster's default.
  std::string memory;
  /// Rows per array task; 0: enough for a task to last about 20 s (from the
  /// rows' typical times), since Slurm spends about a second on each task.
  int rowsPerTask = 0;
  /// At most this many tasks at once (the array's %N); 0: no limit.
  int maxRunning = 0;
  /// Further sbatch options, each as one word ("--account=lab", "--qos=short").
  std::vector<std::string> extraArguments;
  /// The `vimlop` program the tasks run: it must be at the same path on the
  /// cluster's nodes (a shared file system). Default: this process's program.
  std::string program;
  /// The Slurm commands (found on PATH).
  std::string sbatch = "sbatch";
  std::string scontrol = "scontrol";
  std::string squeue = "squeue";
};

/// @brief One submission of a cohort to Slurm, as slurm/submission-<n>.json records it.
struct SlurmSubmission
{
  /// A job array of the submission: Slurm's job id, its tasks and its script.
  struct JobArray
  {
    std::string jobId;
    int firstTask = 0;
    int taskCount = 0;
    std::string script;
  };

  /// 1 for the first submission of the cohort, then 2, 3, ...
  int number = 0;
  std::string submittedUtc;
  /// Each task's rows.
  std::vector<std::vector<std::string>> tasks;
  std::vector<JobArray> arrays;
  /// The merge job, which runs `vimlop cohort merge` once every array ended well.
  std::string mergeJobId;
  /// The settings it was submitted with (a resubmission's defaults).
  SlurmSubmitOptions options;

  /// @brief Every job id of the submission (its arrays, then the merge job).
  std::vector<std::string> jobIds() const;
};

/**
 * @brief Submits the rows `ids` of the cohort in `folder` to Slurm: writes
 * one batch script per job array (slurm/submission-<n>-array-<k>.sbatch:
 * each task runs `vimlop cohort task`), submits them with sbatch, then a
 * merge job that runs `vimlop cohort merge` after all of them
 * (--dependency=afterok), and records the submission.
 * @throws vimlop::Error when there is nothing to submit, sbatch is missing
 * or refuses a job (its message), or the files cannot be written.
 */
SlurmSubmission submitCohortToSlurm(const CohortManifest& manifest, const CohortFolder& folder,
  const std::vector<std::string>& ids, const SlurmSubmitOptions& options);

/// @brief The submissions of the cohort in `folder`, oldest first (none when never submitted).
std::vector<SlurmSubmission> readSlurmSubmissions(const CohortFolder& folder);

/**
 * @brief The cluster's MaxArraySize (scontrol show config): array task ids
 * run from 0 to MaxArraySize - 1.
 * @throws vimlop::Error when scontrol fails or does not say.
 */
int slurmMaxArraySize(const std::string& scontrol = "scontrol");

/**
 * @brief Which of `jobIds` are still queued or running (squeue), each with
 * its state ("PENDING", "RUNNING", ...); an array counts while any of its
 * tasks does.
 * @throws vimlop::Error when squeue cannot be run or fails.
 */
std::vector<std::pair<std::string, std::string>> slurmJobsInQueue(
  const std::vector<std::string>& jobIds, const std::string& squeue = "squeue");

} // namespace vimlop

#endif
