#include <vimlop/Cohort/CohortFolder.h>
#include <vimlop/Cohort/CohortManifest.h>
#include <vimlop/Cohort/SlurmSubmission.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <sys/stat.h>

namespace vimlop
{
namespace
{

namespace fs = std::filesystem;

std::string script(const fs::path& path, const std::string& body)
{
  std::ofstream(path) << "#!/bin/sh\n" << body;
  ::chmod(path.c_str(), 0755);
  return path.string();
}

TEST(SlurmSubmission, ChunksRowsIntoTasksAndTasksIntoArraysUnderMaxArraySize)
{
  const SlurmPlan plan = planSlurmTasks({ "a", "b", "c", "d", "e", "f", "g" }, 2, 3);
  EXPECT_EQ(plan.tasks,
    (std::vector<std::vector<std::string>>{ { "a", "b" }, { "c", "d" }, { "e", "f" }, { "g" } }));
  EXPECT_EQ(plan.arrays, (std::vector<std::pair<int, int>>{ { 0, 3 }, { 3, 1 } }));
  const SlurmPlan one = planSlurmTasks({ "a", "b" }, 5, 1001);
  EXPECT_EQ(one.tasks.size(), 1u);
  EXPECT_EQ(one.arrays, (std::vector<std::pair<int, int>>{ { 0, 1 } }));
  EXPECT_EQ(fixtures::errorMessageOf([] { planSlurmTasks({ "a" }, 0, 10); }),
    "Slurm: at least 1 row per task, not 0");
  EXPECT_EQ(fixtures::errorMessageOf([] { planSlurmTasks({ "a" }, 1, 0); }),
    "Slurm: MaxArraySize must be at least 1, not 0");
}

/// A cohort of three register rows and Slurm commands that only pretend.
struct FakeSlurm
{
  fs::path dir = fixtures::freshTestFolder("cohort-slurm");
  CohortManifest manifest;
  CohortFolder folder{ (dir / "out").string() };
  SlurmSubmitOptions options;

  FakeSlurm()
  {
    std::ofstream(dir / "cohort.csv") << "id,command\na,register\nb,register\nc,register\n";
    this->manifest = readCohortManifest((dir / "cohort.csv").string());
    this->folder.prepare(this->manifest);
    // sbatch numbers its jobs from 1001 and keeps each call's arguments.
    this->options.sbatch = script(dir / "sbatch",
      "n=$(cat '" + (dir / "next").string() +
        "' 2>/dev/null || echo 1001)\n"
        "echo \"$@\" >> '" +
        (dir / "sbatch-calls").string() +
        "'\n"
        "echo $((n + 1)) > '" +
        (dir / "next").string() + "'\necho \"$n;cluster\"\n");
    this->options.scontrol = script(dir / "scontrol",
      "echo 'Configuration data as of now'\necho 'MaxArraySize            = 2'\n");
    this->options.program = "/opt/vimlop bin/vimlop";
    this->options.cpusPerTask = 4;
    this->options.partition = "short";
    this->options.time = "0:10:00";
    this->options.extraArguments = { "--account=lab" };
  }
};

TEST(SlurmSubmission, WritesOneScriptPerArrayAndAMergeJobAfterThem)
{
  FakeSlurm slurm;
  slurm.options.rowsPerTask = 1;
  const SlurmSubmission s =
    submitCohortToSlurm(slurm.manifest, slurm.folder, { "a", "b", "c" }, slurm.options);
  EXPECT_EQ(s.number, 1);
  ASSERT_EQ(s.arrays.size(), 2u); // 3 tasks, at most 2 an array
  EXPECT_EQ(s.arrays[0].jobId, "1001");
  EXPECT_EQ(s.arrays[1].jobId, "1002");
  EXPECT_EQ(s.arrays[1].firstTask, 2);
  EXPECT_EQ(s.mergeJobId, "1003");
  const std::string first = fixtures::fileBytes(s.arrays[0].script);
  const std::string root = slurm.folder.root();
  for (const std::string& line :
    { std::string("#SBATCH --array=0-1\n"), std::string("#SBATCH --cpus-per-task=4\n"),
      std::string("#SBATCH --partition=short\n"), std::string("#SBATCH --time=0:10:00\n"),
      std::string("#SBATCH --account=lab\n"), std::string("unset DISPLAY\n"),
      "exec '/opt/vimlop bin/vimlop' cohort task " + root +
        " --submission 1 --task \"$((0 + SLURM_ARRAY_TASK_ID))\"\n" })
  {
    EXPECT_NE(first.find(line), std::string::npos) << line << " not in\n" << first;
  }
  EXPECT_NE(
    fixtures::fileBytes(s.arrays[1].script).find("#SBATCH --array=0-0\n"), std::string::npos);
  EXPECT_NE(fixtures::fileBytes(s.arrays[1].script).find("--task \"$((2 + SLURM_ARRAY_TASK_ID))\""),
    std::string::npos);
  const std::string merge =
    fixtures::fileBytes(slurm.folder.slurmFolder() + "/submission-1-merge.sbatch");
  EXPECT_NE(merge.find("#SBATCH --dependency=afterok:1001:1002\n"), std::string::npos) << merge;
  EXPECT_NE(
    merge.find("exec '/opt/vimlop bin/vimlop' cohort merge " + root + "\n"), std::string::npos);
  EXPECT_NE(
    fixtures::fileBytes(slurm.dir / "sbatch-calls").find("--parsable " + s.arrays[0].script),
    std::string::npos);

  // The record, read back.
  const std::vector<SlurmSubmission> read = readSlurmSubmissions(slurm.folder);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].jobIds(), (std::vector<std::string>{ "1001", "1002", "1003" }));
  EXPECT_EQ(read[0].tasks, (std::vector<std::vector<std::string>>{ { "a" }, { "b" }, { "c" } }));
  EXPECT_EQ(read[0].options.cpusPerTask, 4);
  EXPECT_EQ(read[0].options.extraArguments, slurm.options.extraArguments);

  // A second submission (the failed rows, say) gets the next number.
  slurm.options.rowsPerTask = 0; // the default: register rows last long enough alone
  const SlurmSubmission again =
    submitCohortToSlurm(slurm.manifest, slurm.folder, { "b" }, slurm.options);
  EXPECT_EQ(again.number, 2);
  EXPECT_EQ(again.options.rowsPerTask, 1);
  EXPECT_EQ(readSlurmSubmissions(slurm.folder).size(), 2u);
}

TEST(SlurmSubmission, SaysWhatSbatchSaidWhenItRefuses)
{
  FakeSlurm slurm;
  slurm.options.sbatch = script(
    slurm.dir / "sbatch", "echo 'sbatch: error: invalid partition specified: short' >&2\nexit 1\n");
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] { submitCohortToSlurm(slurm.manifest, slurm.folder, { "a" }, slurm.options); }),
    "sbatch refused '" + slurm.folder.slurmFolder() +
      "/submission-1-array-1.sbatch': sbatch: error: invalid partition specified: short");
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] { submitCohortToSlurm(slurm.manifest, slurm.folder, {}, slurm.options); }),
    "nothing to submit: every row has its result or is running");
  slurm.options.scontrol = script(slurm.dir / "scontrol", "echo 'ClusterName = x'\n");
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] { submitCohortToSlurm(slurm.manifest, slurm.folder, { "a" }, slurm.options); }),
    "scontrol show config does not give MaxArraySize");
}

TEST(SlurmSubmission, FindsTheCohortsJobsInTheQueueByArrayOrJobId)
{
  const fs::path dir = fixtures::freshTestFolder("cohort-squeue");
  const std::string squeue = script(dir / "squeue",
    "printf '1001|1005|RUNNING\\n1001|1001|PENDING\\n77|77|RUNNING\\n1003|1003|PENDING\\n'\n");
  EXPECT_EQ(slurmJobsInQueue({ "1001", "1002", "1003" }, squeue),
    (std::vector<std::pair<std::string, std::string>>{
      { "1001", "RUNNING" }, { "1001", "PENDING" }, { "1003", "PENDING" } }));
  EXPECT_TRUE(slurmJobsInQueue({}, squeue).empty());
  const std::string failing = script(dir / "squeue-down",
    "echo 'slurm_load_jobs error: Unable to contact slurm controller' >&2\nexit 1\n");
  EXPECT_EQ(fixtures::errorMessageOf([&] { slurmJobsInQueue({ "1" }, failing); }),
    "squeue failed: slurm_load_jobs error: Unable to contact slurm controller");
}

} // namespace
} // namespace vimlop
