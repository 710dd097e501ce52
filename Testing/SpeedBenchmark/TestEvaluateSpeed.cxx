// `vimlop evaluate speed` end to end, on the smallest run (6 frames, 1
// thread): its JSON's layout, and that the stages' times add up.

#include <vimlop/Core/ChildProcess.h>

#include "TestFolders.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>

namespace vimlop
{
namespace
{

namespace fs = std::filesystem;

TEST(EvaluateSpeed, TimesEachStageOfASixFrameRunAndTheirSumStaysWithinItsWallTime)
{
  const fs::path dir = fs::path(VIMLOP_TEST_OUTPUT_DIR) / "evaluate-speed";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const ChildProcessResult r =
    runChildProcess({ VIMLOP_PROGRAM, "evaluate", "speed", "--ct", VIMLOP_CRANIUM, "--frames", "6",
                      "--threads", "1", "--seed", "1", "--keep", (dir / "work").string(), "--out",
                      (dir / "speed.json").string() },
      (dir / "stdout.txt").string(), (dir / "stderr.txt").string());
  ASSERT_EQ(r.exitCode, 0) << fixtures::fileBytes(dir / "stderr.txt");
  // Progress on stderr, the table on stdout.
  EXPECT_NE(
    fixtures::fileBytes(dir / "stderr.txt").find("vimlop evaluate speed: 6 frames, 1 thread: "),
    std::string::npos);
  const std::string table = fixtures::fileBytes(dir / "stdout.txt");
  EXPECT_EQ(table.rfind("frames threads   wall s result s  frames   model", 0), 0u) << table;
  EXPECT_NE(table.find("\n     6       1 "), std::string::npos) << table;
  // The user's files were registered as a user would: a whole result folder.
  EXPECT_TRUE(fs::exists(dir / "work" / "register-6-t1" / "result.json"));
  EXPECT_TRUE(fs::exists(dir / "work" / "register-6-t1" / "report" / "index.html"));

  const nlohmann::json j = nlohmann::json::parse(fixtures::fileBytes(dir / "speed.json"));
  EXPECT_EQ(j.at("benchmark"), "vimlop evaluate speed");
  EXPECT_EQ(j.at("seed"), 1);
  EXPECT_EQ(j.at("upright_deg"), 10.0);
  EXPECT_TRUE(j.at("version").is_string());
  EXPECT_EQ(j.at("program"), VIMLOP_PROGRAM);
  EXPECT_TRUE(j.at("commit").is_string() || j.at("commit").is_null());
  const nlohmann::json& machine = j.at("machine");
  EXPECT_TRUE(machine.at("cpu_model").is_string());
  EXPECT_GE(machine.at("logical_cpus").get<int>(), 1);
  EXPECT_EQ(machine.at("load_average_start").size(), 3u);
  EXPECT_EQ(machine.at("load_average_end").size(), 3u);
  ASSERT_EQ(j.at("sequences").size(), 1u);
  EXPECT_GT(j.at("sequences")[0].at("simulate_wall_s").get<double>(), 0.0);
  // One thread count: nothing to scale against.
  EXPECT_TRUE(j.at("scaling").empty());
  EXPECT_TRUE(j.at("warnings").is_array());

  ASSERT_EQ(j.at("runs").size(), 1u);
  const nlohmann::json& run = j.at("runs")[0];
  EXPECT_EQ(run.at("frames"), 6);
  EXPECT_EQ(run.at("threads"), 1);
  std::vector<std::string> names;
  double wallSumS = 0.0;
  double resultSumS = 0.0;
  for (const nlohmann::json& s : run.at("timings").at("stages"))
  {
    names.push_back(s.at("name"));
    EXPECT_GE(s.at("wall_s").get<double>(), 0.0) << names.back();
    EXPECT_GE(s.at("cpu_s").get<double>(), 0.0) << names.back();
    wallSumS += s.at("wall_s").get<double>();
    if (names.size() <= 9)
    {
      resultSumS += s.at("wall_s").get<double>();
    }
  }
  // The registered poses come first among the outputs, result.json last.
  EXPECT_EQ(names,
    (std::vector<std::string>{ "frames", "model", "contours", "sfm", "scale", "data", "starts",
      "screening", "final", "record", "poses", "pictures", "camera_path", "video", "report",
      "result_json" }));
  const double wallS = run.at("wall_s").get<double>();
  EXPECT_NEAR(run.at("timings").at("total_wall_s").get<double>(), wallSumS, 1e-9);
  // The result is usable at the child's own mark: after the registration and
  // the poses (the stages, and its start-up before them), before the video.
  const nlohmann::json& marks = run.at("timings").at("marks");
  ASSERT_EQ(marks.size(), 1u);
  EXPECT_EQ(marks[0].at("name"), "result_usable");
  const double usableS = marks[0].at("at_wall_s").get<double>();
  EXPECT_NEAR(run.at("result_s").get<double>(), usableS, 1e-9);
  EXPECT_GE(usableS, resultSumS);
  EXPECT_LE(usableS, wallS - run.at("timings").at("stages")[13].at("wall_s").get<double>());
  EXPECT_NEAR(run.at("outputs_s").get<double>(), wallSumS - resultSumS, 1e-9);
  EXPECT_NEAR(run.at("unaccounted_s").get<double>(), wallS - wallSumS, 1e-9);
  // The stages cover the run: within its wall time, and most of it (the
  // rest is the start-up, reading the small files and the exit).
  EXPECT_LE(wallSumS, wallS);
  EXPECT_GE(wallSumS, 0.5 * wallS);
  // The child's own peak and CPU: a CT, a model and frames are more than a few MiB.
  EXPECT_GT(run.at("peak_resident_mib").get<double>(), 50.0);
  EXPECT_GE(run.at("rusage_max_rss_mib").get<double>(), run.at("peak_resident_mib").get<double>());
  EXPECT_GT(run.at("user_cpu_s").get<double>(), 0.0);
  EXPECT_NEAR(run.at("cpu_per_wall").get<double>(),
    (run.at("user_cpu_s").get<double>() + run.at("system_cpu_s").get<double>()) / wallS, 1e-9);
}

} // namespace
} // namespace vimlop
