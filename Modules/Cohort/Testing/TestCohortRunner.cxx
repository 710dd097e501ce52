#include <vimlop/Cohort/CohortFolder.h>
#include <vimlop/Cohort/CohortManifest.h>
#include <vimlop/Cohort/CohortRunner.h>

#include "ErrorMessage.h"
#include "FakeVimlop.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

namespace vimlop
{
namespace
{

namespace fs = std::filesystem;

/// A cohort of the fake program: its manifest's folder (with a CT file
/// `ct.nii`), the manifest and the cohort folder.
struct FakeCohort
{
  fs::path dir;
  std::string program;
  std::string manifestPath;
  CohortManifest manifest;
  CohortFolder folder{ "unset" };

  explicit FakeCohort(const std::string& csvRows)
  {
    this->dir = fixtures::freshTestFolder("cohort-runner");
    this->program = fixtures::writeFakeVimlop(this->dir);
    fs::create_directories(this->dir / "study");
    std::ofstream(this->dir / "study" / "ct.nii") << "a CT";
    this->write(csvRows);
    this->folder = CohortFolder((this->dir / "out").string());
    this->folder.prepare(this->manifest);
  }

  void write(const std::string& csvRows)
  {
    this->manifestPath = (this->dir / "study" / "cohort.csv").string();
    std::ofstream(this->manifestPath) << "id,command,ct,options\n" << csvRows;
    this->manifest = readCohortManifest(this->manifestPath);
  }

  CohortRunReport run(CohortRunOptions options = CohortRunOptions()) const
  {
    options.program = this->program;
    options.virtualDisplay = false;
    return runCohort(this->manifest, this->folder, options);
  }

  /// How often the fake program ran.
  int calls() const
  {
    std::ifstream in(this->dir / "calls.txt");
    int lines = 0;
    for (std::string line; std::getline(in, line);)
    {
      ++lines;
    }
    return lines;
  }

  CohortRowState state(const std::string& id) const
  {
    return cohortRowState(this->folder, *this->manifest.find(id));
  }
};

TEST(CohortRunner, RunsEveryRowInTheManifestsFolderAndRecordsEachAttempt)
{
  const FakeCohort cohort("a,register,ct.nii,\nb,register,ct.nii,\nc,register,ct.nii,\n");
  CohortRunOptions options;
  options.jobs = 2;
  options.threadsPerJob = 3;
  int progress = 0;
  options.onRowDone = [&](const CohortRowOutcome&, int done, int total)
  {
    EXPECT_EQ(done, ++progress);
    EXPECT_EQ(total, 3);
  };
  const CohortRunReport report = cohort.run(options);
  EXPECT_EQ(report.selected, 3);
  EXPECT_EQ(report.alreadyComplete, 0);
  ASSERT_EQ(report.outcomes.size(), 3u);
  EXPECT_EQ(report.count(CohortRowState::Complete), 3);
  EXPECT_EQ(progress, 3);
  const CohortRowOutcome& a = report.outcomes[0];
  EXPECT_EQ(a.id, "a");
  EXPECT_EQ(a.summary, "camera error 0.200 mm, contour error 1.50 px");
  const std::string result = fixtures::fileBytes(cohort.folder.rowFolder("a") + "/result.json");
  EXPECT_NE(result.find("\"cwd\": \"" + fs::canonical(cohort.dir / "study").string() + "\""),
    std::string::npos)
    << result;
  EXPECT_NE(result.find("\"threads\": 3"), std::string::npos);
  const CohortRowStatus status = readCohortRowStatus(cohort.folder.statusPath("a"));
  ASSERT_EQ(status.attempts.size(), 1u);
  EXPECT_EQ(status.digest, cohort.manifest.rows[0].digest());
  EXPECT_EQ(status.attempts[0].state, CohortRowState::Complete);
  EXPECT_EQ(status.attempts[0].exitCode, 0);
  EXPECT_EQ(status.attempts[0].threads, 3);
  EXPECT_EQ(status.attempts[0].host, hostName());
  EXPECT_EQ(status.attempts[0].startedUtc.size(), 20u);
  EXPECT_NE(fixtures::fileBytes(cohort.folder.logPath("a")).find("fake vimlop: register in"),
    std::string::npos);
  EXPECT_EQ(cohort.state("c"), CohortRowState::Complete);
}

TEST(CohortRunner, AFailedRowDoesNotStopTheOthersAndRunsAloneAfterItsFix)
{
  const FakeCohort cohort("a,register,ct.nii,\nbroken,register,missing.nii,\nc,register,ct.nii,\n");
  const CohortRunReport first = cohort.run();
  EXPECT_EQ(first.count(CohortRowState::Complete), 2);
  ASSERT_EQ(first.count(CohortRowState::Failed), 1);
  EXPECT_EQ(first.outcomes[1].id, "broken");
  EXPECT_EQ(first.outcomes[1].attempt.error, "'missing.nii': no such file or folder");
  EXPECT_EQ(first.outcomes[1].attempt.exitCode, 1);
  EXPECT_EQ(cohort.state("broken"), CohortRowState::Failed);
  const auto resultTime = fs::last_write_time(cohort.folder.rowFolder("a") + "/result.json");

  // The fix, then only the failed row runs.
  std::ofstream(cohort.dir / "study" / "missing.nii") << "now here";
  CohortRunOptions options;
  options.onlyFailed = true;
  const CohortRunReport second = cohort.run(options);
  ASSERT_EQ(second.outcomes.size(), 1u);
  EXPECT_EQ(second.outcomes[0].id, "broken");
  EXPECT_EQ(second.outcomes[0].state, CohortRowState::Complete);
  EXPECT_EQ(second.alreadyComplete, 2);
  EXPECT_EQ(cohort.calls(), 4);
  EXPECT_EQ(fs::last_write_time(cohort.folder.rowFolder("a") + "/result.json"), resultTime);
  EXPECT_EQ(readCohortRowStatus(cohort.folder.statusPath("broken")).attempts.size(), 2u);
}

TEST(CohortRunner, ARunResumesWithoutRedoingCompleteRows)
{
  const FakeCohort cohort("a,register,ct.nii,\nb,register,ct.nii,\nc,register,ct.nii,\n");
  CohortRunOptions some;
  some.rows = { "c", "a" };
  EXPECT_EQ(cohort.run(some).outcomes.size(), 2u);
  EXPECT_EQ(cohort.state("b"), CohortRowState::NotRun);
  const CohortRunReport rest = cohort.run();
  EXPECT_EQ(rest.selected, 3);
  EXPECT_EQ(rest.alreadyComplete, 2);
  ASSERT_EQ(rest.outcomes.size(), 1u);
  EXPECT_EQ(rest.outcomes[0].id, "b");
  EXPECT_EQ(cohort.calls(), 3);
  EXPECT_TRUE(cohort.run().outcomes.empty());
  EXPECT_EQ(cohort.calls(), 3);
  some.rows = { "z" };
  EXPECT_EQ(fixtures::errorMessageOf([&] { cohort.run(some); }),
    "no row 'z' in the manifest '" + cohort.manifestPath + "'");
}

TEST(CohortRunner, AFlaggedRowIsAResultNotAFailure)
{
  const FakeCohort cohort("a,register,ct.nii,--flag-it\n");
  const CohortRunReport report = cohort.run();
  ASSERT_EQ(report.outcomes.size(), 1u);
  EXPECT_EQ(report.outcomes[0].state, CohortRowState::Flagged);
  EXPECT_EQ(report.outcomes[0].attempt.exitCode, 3);
  EXPECT_EQ(report.outcomes[0].summary,
    "camera error 0.200 mm, contour error 1.50 px; contour error too high");
  EXPECT_EQ(cohort.state("a"), CohortRowState::Flagged);
  EXPECT_TRUE(cohort.run().outcomes.empty());
}

TEST(CohortRunner, LeavesARowAloneWhileAnotherRunHoldsIt)
{
  const FakeCohort cohort("a,register,ct.nii,\nb,register,ct.nii,\n");
  const CohortRowLock elsewhere(cohort.folder.lockPath("a"));
  ASSERT_TRUE(elsewhere.held());
  EXPECT_EQ(cohort.state("a"), CohortRowState::Running);
  std::vector<std::string> notes;
  CohortRunOptions options;
  options.onNote = [&](const std::string& note) { notes.push_back(note); };
  const CohortRunReport report = cohort.run(options);
  ASSERT_EQ(report.outcomes.size(), 1u);
  EXPECT_EQ(report.outcomes[0].id, "b");
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0], "'a' runs elsewhere (its lock is held); left to that run");
  EXPECT_EQ(cohort.calls(), 1);
}

TEST(CohortRunner, AChangedRowRunsAgainAndItsOldResultNeverPassesForTheNewRow)
{
  FakeCohort cohort("a,register,ct.nii,\n");
  cohort.run();
  cohort.write("a,register,ct.nii,--sleep 0\n");
  EXPECT_EQ(cohort.state("a"), CohortRowState::Changed);
  EXPECT_EQ(cohort.run().count(CohortRowState::Complete), 1);
  EXPECT_EQ(cohort.state("a"), CohortRowState::Complete);
  // A re-run that fails leaves the old result, still not the new row's.
  cohort.write("a,register,gone.nii,\n");
  EXPECT_EQ(cohort.run().count(CohortRowState::Failed), 1);
  EXPECT_EQ(cohort.state("a"), CohortRowState::Changed);
  EXPECT_TRUE(fs::exists(cohort.folder.rowFolder("a") + "/result.json"));
}

TEST(CohortRunner, StoppingARunStopsItsRowsAndRecordsThemAsInterrupted)
{
  const FakeCohort cohort("slow,register,ct.nii,--sleep 30\nnext,register,ct.nii,\n");
  const auto start = std::chrono::steady_clock::now();
  CohortRunOptions options;
  options.keepGoing = [&]
  { return std::chrono::steady_clock::now() - start < std::chrono::milliseconds(500); };
  const CohortRunReport report = cohort.run(options);
  EXPECT_TRUE(report.interrupted);
  ASSERT_EQ(report.outcomes.size(), 1u);
  EXPECT_EQ(report.outcomes[0].state, CohortRowState::Interrupted);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 8.0);
  EXPECT_EQ(cohort.state("slow"), CohortRowState::Interrupted);
  EXPECT_EQ(cohort.state("next"), CohortRowState::NotRun);
  // A runner killed outright leaves its attempt "running", and no lock: interrupted.
  CohortRowStatus status;
  status.id = "next";
  status.attempts.emplace_back().state = CohortRowState::Running;
  writeCohortRowStatus(status, cohort.folder.statusPath("next"));
  EXPECT_EQ(cohort.state("next"), CohortRowState::Interrupted);
}

TEST(CohortRunner, SaysWhyARowFailedInOneLine)
{
  EXPECT_EQ(cohortFailureLine("reading...\nvimlop: error: 'x.nii': no such file\nbye\n", 1, 0),
    "'x.nii': no such file");
  EXPECT_EQ(cohortFailureLine("step 1\r step 2\rstep 3\n", 2, 0),
    "exited with code 2; its last line: 'step 3'");
  EXPECT_EQ(cohortFailureLine("", -1, 9), "ended by signal 9 (Killed)");
}

TEST(CohortRunner, RefusesAFolderThatIsNotACohortsOrHoldsAnotherOne)
{
  const FakeCohort cohort("a,register,ct.nii,\n");
  const fs::path other = cohort.dir / "someone-elses";
  fs::create_directories(other);
  std::ofstream(other / "notes.txt") << "mine";
  EXPECT_EQ(
    fixtures::errorMessageOf([&] { CohortFolder(other.string()).prepare(cohort.manifest); }),
    "'" + other.string() +
      "': a folder with other files, not a cohort folder; choose another --out");
  CohortManifest another = cohort.manifest;
  another.path = (cohort.dir / "another.csv").string();
  EXPECT_EQ(fixtures::errorMessageOf([&] { cohort.folder.prepare(another); }),
    "'" + cohort.folder.root() + "' holds the cohort of '" + cohort.manifestPath + "', not of '" +
      another.path + "'; choose another --out");
  EXPECT_EQ(fixtures::errorMessageOf([&] { CohortFolder(other.string()).manifest({}); }),
    "'" + other.string() + "': not a cohort folder (no cohort.json)");
  // The folder's own copy, with the rows' folder of the original.
  const CohortManifest copy = cohort.folder.manifest({});
  EXPECT_EQ(copy.path, cohort.manifestPath);
  EXPECT_EQ(copy.folder, (cohort.dir / "study").string());
  EXPECT_EQ(copy.rows.at(0).digest(), cohort.manifest.rows.at(0).digest());
}

} // namespace
} // namespace vimlop
