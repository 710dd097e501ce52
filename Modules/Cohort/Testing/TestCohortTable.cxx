#include <vimlop/Cohort/CohortFolder.h>
#include <vimlop/Cohort/CohortManifest.h>
#include <vimlop/Cohort/CohortReportPage.h>
#include <vimlop/Cohort/CohortRunner.h>
#include <vimlop/Cohort/CohortTable.h>

#include "FakeVimlop.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace vimlop
{
namespace
{

namespace fs = std::filesystem;
using nlohmann::json;

/// The fake program's cohort run into `out` with `threads` per row.
CohortTable runAndMerge(const fs::path& dir, const std::string& out, int threads)
{
  const CohortManifest manifest = readCohortManifest((dir / "study" / "cohort.csv").string());
  const CohortFolder folder((dir / out).string());
  folder.prepare(manifest);
  CohortRunOptions options;
  options.program = (dir / "fake-vimlop").string();
  options.virtualDisplay = false;
  options.threadsPerJob = threads;
  options.jobs = threads;
  runCohort(manifest, folder, options);
  return mergeCohortTable(manifest, folder);
}

/// The table's CSV without its volatile columns.
std::string steadyCsv(const CohortTable& table)
{
  CohortTable steady = table;
  steady.columns.clear();
  for (const std::string& c : table.columns)
  {
    if (std::find(table.volatileColumns.begin(), table.volatileColumns.end(), c) ==
      table.volatileColumns.end())
    {
      steady.columns.push_back(c);
    }
  }
  return steady.csv();
}

fs::path fakeStudy()
{
  const fs::path dir = fixtures::freshTestFolder("cohort-table");
  fixtures::writeFakeVimlop(dir);
  fs::create_directories(dir / "study");
  std::ofstream(dir / "study" / "ct.nii") << "a CT";
  std::ofstream(dir / "study" / "cohort.csv") << "id,command,ct,options\n"
                                                 "reg,register,ct.nii,\n"
                                                 "flagged,register,ct.nii,--flag-it\n"
                                                 "p1,evaluate synthetic,,--seed 4\n"
                                                 "broken,register,\"no, such.nii\",\n";
  return dir;
}

TEST(CohortTable, HoldsEveryRowsStateFiguresAndProvenance)
{
  const fs::path dir = fakeStudy();
  const CohortTable table = runAndMerge(dir, "out", 1);
  ASSERT_EQ(table.rows.size(), 4u);
  const json& reg = table.rows[0];
  EXPECT_EQ(reg.at("state"), "complete");
  EXPECT_DOUBLE_EQ(reg.at("contour_error_px").get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(reg.at("scale").get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(reg.at("camera_position_error_mm_mean").get<double>(), 0.2);
  EXPECT_DOUBLE_EQ(reg.at("camera_position_error_mm_max").get<double>(), 0.3);
  EXPECT_EQ(reg.at("input.ct.sha256"), "abc");
  EXPECT_EQ(reg.at("output"), "jobs/reg/result.json");
  EXPECT_EQ(reg.at("command_line"), "vimlop register --ct ct.nii");
  EXPECT_EQ(table.rows[1].at("state"), "flagged");
  EXPECT_EQ(table.rows[1].at("failure_reason"), "contour error too high");
  const json& p1 = table.rows[2];
  EXPECT_EQ(p1.at("command"), "evaluate synthetic");
  EXPECT_DOUBLE_EQ(p1.at("methods.vimlop.tre_mm.median").get<double>(), 0.07);
  EXPECT_EQ(p1.at("seed"), 4);
  EXPECT_EQ(p1.at("vimlop_version"), VIMLOP_VERSION); // the runner's: P1's report has none
  const json& broken = table.rows[3];
  EXPECT_EQ(broken.at("state"), "failed");
  EXPECT_EQ(broken.at("error"), "'no, such.nii': no such file or folder");
  EXPECT_FALSE(broken.contains("contour_error_px"));
  // Group order: id, command, state, error; figures; provenance.
  EXPECT_EQ(std::vector<std::string>(table.columns.begin(), table.columns.begin() + 4),
    (std::vector<std::string>{ "id", "command", "state", "error" }));
  const auto position = [&](const std::string& c)
  { return std::find(table.columns.begin(), table.columns.end(), c) - table.columns.begin(); };
  EXPECT_LT(position("contour_error_px"), position("methods.vimlop.tre_mm.median"));
  EXPECT_LT(position("methods.vimlop.tre_mm.median"), position("command_line"));
  for (const char* v :
    { "runtime_s", "methods.vimlop.runtime_s.median", "host", "wall_s", "threads", "started" })
  {
    EXPECT_NE(std::find(table.volatileColumns.begin(), table.volatileColumns.end(), v),
      table.volatileColumns.end())
      << v;
  }
  // CSV: one line per row after the header, the error quoted for its comma.
  const std::string csv = table.csv();
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
  EXPECT_NE(csv.find(",\"'no, such.nii': no such file or folder\","), std::string::npos);
  EXPECT_EQ(table.toJson().at("volatile_columns"), json(table.volatileColumns));
}

TEST(CohortTable, IsTheSameOutsideItsVolatileColumnsWhateverTheThreadsAndTheFolder)
{
  const fs::path dir = fakeStudy();
  const CohortTable one = runAndMerge(dir, "one-thread", 1);
  const CohortTable two = runAndMerge(dir, "two-threads", 2);
  EXPECT_NE(one.csv(), two.csv()); // threads, times
  EXPECT_EQ(steadyCsv(one), steadyCsv(two));
}

TEST(CohortReportPage, DrawsTheDistributionsAndListsTheRowsWithoutAResult)
{
  const fs::path dir = fakeStudy();
  const CohortTable table = runAndMerge(dir, "out", 1);
  writeCohortReportPage(table, "cohort.csv", (dir / "out" / "report").string());
  const std::string page = fixtures::fileBytes(dir / "out" / "report" / "index.html");
  EXPECT_NE(page.find("4 rows: 2 complete, 1 failed, 1 flagged"), std::string::npos) << page;
  EXPECT_NE(page.find("<td>broken</td><td>register</td><td>failed</td><td>'no, such.nii': no "
                      "such file or folder</td><td><a href=\"../logs/broken.log\">log</a>"),
    std::string::npos);
  EXPECT_EQ(page.find("<td>reg</td><td>register</td><td>failed"), std::string::npos);
  EXPECT_NE(page.find("contour error, px (n 2, median 1.5, p95 1.5)"), std::string::npos);
}

TEST(CohortReportPage, AHistogramHasABarPerBinAndSaysWhenItHasNothing)
{
  const std::string svg = histogramSvg({ 1, 2, 2, 3, 3, 3, 4, 9, 10 }, "error <mm>");
  // sqrt(9) = 3 bins over [1, 10]: [1, 4) holds 6 values, [4, 7) one, [7, 10] two.
  std::istringstream lines(svg);
  std::vector<std::string> bars;
  for (std::string line; std::getline(lines, line);)
  {
    if (line.rfind("<rect", 0) == 0)
    {
      bars.push_back(line.substr(line.find("<title>") + 7));
    }
  }
  EXPECT_EQ(
    bars, (std::vector<std::string>{ "6</title></rect>", "1</title></rect>", "2</title></rect>" }));
  EXPECT_NE(svg.find("error &lt;mm&gt; (n 9, median 3"), std::string::npos);
  EXPECT_NE(histogramSvg({}, "runtime").find("runtime: no row has this figure"), std::string::npos);
  const std::string equal = histogramSvg({ 5, 5 }, "x");
  EXPECT_NE(equal.find("<title>2</title>"), std::string::npos); // one bin holds both
  EXPECT_EQ(equal.find("<rect", equal.find("<rect") + 1), std::string::npos);
}

} // namespace
} // namespace vimlop
