#include <vimlop/Evaluation/MachineDescription.h>
#include <vimlop/Evaluation/SpeedBenchmark.h>

#include "ErrorMessage.h"

#include <gtest/gtest.h>

namespace vimlop
{
namespace
{

SpeedBenchmarkOptions validOptions()
{
  SpeedBenchmarkOptions o;
  o.ctPath = "ct.nii";
  o.workFolder = "work";
  return o;
}

std::string validationMessage(const SpeedBenchmarkOptions& o)
{
  return fixtures::errorMessageOf([&] { o.validate(); });
}

TEST(SpeedBenchmarkOptions, TheDefaultsWithACtAndAWorkFolderAreValid)
{
  EXPECT_EQ(validationMessage(validOptions()), "no error");
  EXPECT_EQ(validOptions().frameCounts, (std::vector<int>{ 6, 30, 60, 100 }));
  EXPECT_EQ(validOptions().threadCounts, (std::vector<int>{ 1, 2 }));
}

TEST(SpeedBenchmarkOptions, RefusesAMissingCtOrWorkFolder)
{
  SpeedBenchmarkOptions o = validOptions();
  o.ctPath.clear();
  EXPECT_EQ(validationMessage(o), "speed benchmark: give the CT (--ct)");
  o = validOptions();
  o.workFolder.clear();
  EXPECT_EQ(validationMessage(o), "speed benchmark: no work folder given");
}

TEST(SpeedBenchmarkOptions, RefusesASequenceOfOneFrame)
{
  SpeedBenchmarkOptions o = validOptions();
  o.frameCounts = { 6, 1 };
  EXPECT_EQ(validationMessage(o),
    "speed benchmark: --frames: each frame count must be from 2 to 10000, got 1");
}

TEST(SpeedBenchmarkOptions, RefusesNoZeroOrNegativeThreadCounts)
{
  SpeedBenchmarkOptions o = validOptions();
  o.threadCounts = { 0 };
  EXPECT_EQ(validationMessage(o),
    "speed benchmark: --threads: each thread count must be from 1 to 1024, got 0");
  o.threadCounts = { 2, -1 };
  EXPECT_EQ(validationMessage(o),
    "speed benchmark: --threads: each thread count must be from 1 to 1024, got -1");
  o.threadCounts.clear();
  EXPECT_EQ(validationMessage(o), "speed benchmark: --threads: give at least one thread count");
}

TEST(SpeedBenchmarkOptions, RefusesANegativeStep)
{
  SpeedBenchmarkOptions o = validOptions();
  o.stepMm = 0.2;
  EXPECT_EQ(validationMessage(o), "no error");
  o.stepMm = -0.5;
  EXPECT_EQ(validationMessage(o),
    "speed benchmark: --step-mm: must be zero (simulate's default) or positive, got -0.5");
}

TEST(SpeedBenchmarkOptions, HoldsTheScopeUprightLikeTheDemoAndRefusesARollOver180Degrees)
{
  SpeedBenchmarkOptions o = validOptions();
  EXPECT_EQ(o.uprightRollDeg, 10.0);
  o.uprightRollDeg = -1.0; // any roll
  EXPECT_EQ(validationMessage(o), "no error");
  o.uprightRollDeg = 200.0;
  EXPECT_EQ(validationMessage(o),
    "speed benchmark: --upright-deg: must be at most 180 (negative: any roll), got 200");
}

TEST(SpeedBenchmarkOptions, RefusesACountListedTwice)
{
  SpeedBenchmarkOptions o = validOptions();
  o.frameCounts = { 6, 30, 6 };
  EXPECT_EQ(validationMessage(o), "speed benchmark: --frames: 6 is listed twice");
}

TEST(SpeedBenchmarkOptions, ReadsCountsAndRefusesWhatIsNotAWholeNumber)
{
  EXPECT_EQ(
    SpeedBenchmarkOptions::parseCounts("6,30,60", "--frames"), (std::vector<int>{ 6, 30, 60 }));
  EXPECT_EQ(SpeedBenchmarkOptions::parseCounts("-1", "--threads"), (std::vector<int>{ -1 }));
  for (const char* bad : { "", "six", "6,,30", "6,", "2.5", "6 30" })
  {
    EXPECT_EQ(
      fixtures::errorMessageOf([&] { SpeedBenchmarkOptions::parseCounts(bad, "--frames"); }),
      std::string("--frames: expected whole numbers separated by commas, got '") + bad + "'")
      << bad;
  }
}

/// A run of `frames` frames on `threads` threads with the given stage wall times.
SpeedBenchmarkRun runOf(
  int frames, int threads, double wallS, const std::vector<std::pair<std::string, double>>& stages)
{
  SpeedBenchmarkRun run;
  run.frames = frames;
  run.threads = threads;
  run.wallS = wallS;
  run.peakResidentMiB = 512.0;
  run.userCpuS = 0.75 * threads * wallS;
  for (const auto& [name, seconds] : stages)
  {
    run.stages.set(name, seconds, threads * seconds);
  }
  return run;
}

SpeedBenchmarkReport twoThreadReport()
{
  SpeedBenchmarkReport report;
  report.runs = { runOf(6, 1, 10.0, { { "model", 2.0 }, { "final", 6.0 }, { "video", 1.0 } }),
    runOf(6, 2, 6.0, { { "model", 2.0 }, { "final", 3.0 }, { "video", 0.5 } }) };
  return report;
}

TEST(SpeedBenchmarkRun, TheResultIsUsableAfterEveryStageBeforeTheOutputs)
{
  const SpeedBenchmarkRun run = runOf(30, 1, 20.0,
    { { "frames", 1.0 }, { "sfm", 4.0 }, { "final", 8.0 }, { "record", 0.5 }, { "pictures", 0.25 },
      { "video", 2.0 }, { "camera_path", 0.25 }, { "result_json", 0.5 }, { "report", 1.5 } });
  EXPECT_DOUBLE_EQ(run.resultS(), 13.0);
  EXPECT_DOUBLE_EQ(run.outputsS(), 5.0);
  EXPECT_DOUBLE_EQ(run.unaccountedS(), 2.0);
  EXPECT_TRUE(SpeedBenchmarkRun::isOutputStage("report"));
  EXPECT_FALSE(SpeedBenchmarkRun::isOutputStage("screening"));
}

TEST(SpeedBenchmarkRun, TheResultIsUsableAtTheRunsOwnMarkWhenItHasOne)
{
  SpeedBenchmarkRun run = runOf(30, 1, 20.0,
    { { "frames", 1.0 }, { "sfm", 4.0 }, { "final", 8.0 }, { "record", 0.5 }, { "poses", 0.25 },
      { "pictures", 0.25 }, { "video", 2.0 }, { "report", 1.5 }, { "result_json", 0.5 } });
  // The start-up before the first stage counts: the user waited for it too.
  run.stages.mark("result_usable", 14.0);
  EXPECT_DOUBLE_EQ(run.resultS(), 14.0);
  EXPECT_DOUBLE_EQ(run.outputsS(), 5.0);
  EXPECT_TRUE(SpeedBenchmarkRun::isOutputStage("poses"));
}

TEST(SpeedBenchmarkReport, ScalingIsTheWallRatioToTheFewestThreadsAndItsEfficiency)
{
  const SpeedBenchmarkReport report = twoThreadReport();
  const SpeedBenchmarkRun& one = report.runs[0];
  const SpeedBenchmarkRun& two = report.runs[1];
  EXPECT_EQ(report.baseOf(two), &one);
  const SpeedBenchmarkReport::Scaling finalPhase = SpeedBenchmarkReport::scaling(one, two, "final");
  ASSERT_TRUE(finalPhase.speedup && finalPhase.efficiency);
  EXPECT_DOUBLE_EQ(*finalPhase.speedup, 2.0);
  EXPECT_DOUBLE_EQ(*finalPhase.efficiency, 1.0);
  const SpeedBenchmarkReport::Scaling model = SpeedBenchmarkReport::scaling(one, two, "model");
  EXPECT_DOUBLE_EQ(*model.speedup, 1.0);
  EXPECT_DOUBLE_EQ(*model.efficiency, 0.5);
  EXPECT_NEAR(*SpeedBenchmarkReport::scaling(one, two, "total").speedup, 10.0 / 6.0, 1e-12);
  EXPECT_DOUBLE_EQ(*SpeedBenchmarkReport::scaling(one, two, "result").speedup, 8.0 / 5.0);
  // A stage one run did not time has no ratio.
  EXPECT_FALSE(SpeedBenchmarkReport::scaling(one, two, "screening").speedup);
}

TEST(SpeedBenchmarkReport, ItsTableHasARowPerRunAndAColumnPerStage)
{
  const std::vector<std::string> lines = twoThreadReport().tableLines();
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(
    lines[0], "frames threads   wall s result s   model   final   video CPU/wall  peak MiB");
  EXPECT_EQ(
    lines[1], "     6       1    10.00     8.00    2.00    6.00    1.00     0.75       512");
  EXPECT_EQ(
    lines[2], "     6       2     6.00     5.00    2.00    3.00    0.50     1.50       512");
  const std::vector<std::string> scaling = twoThreadReport().scalingLines();
  ASSERT_EQ(scaling.size(), 1u);
  EXPECT_EQ(scaling[0],
    "6 frames, 1 -> 2 threads: speed-up (efficiency) total 1.67 (0.83), result 1.60 (0.80); "
    "model 1.00 (0.50) final 2.00 (1.00) video 2.00 (1.00)");
}

TEST(SpeedBenchmarkReport, ItsJsonHoldsTheMachineTheRunsAndTheScaling)
{
  SpeedBenchmarkReport report = twoThreadReport();
  report.machine.cpuModel = "Test CPU";
  report.machine.logicalCpus = 2;
  report.machine.loadAverage = { 0.5, 0.25, 0.125 };
  report.simulateWallS = { { 6, 3.5 } };
  const nlohmann::json j = report.toJson();
  EXPECT_EQ(j.at("machine").at("cpu_model"), "Test CPU");
  EXPECT_EQ(j.at("machine").at("load_average_start")[1], 0.25);
  EXPECT_TRUE(j.at("machine").at("load_average_end").is_null());
  EXPECT_TRUE(j.at("commit").is_null());
  EXPECT_EQ(j.at("sequences")[0].at("simulate_wall_s"), 3.5);
  ASSERT_EQ(j.at("runs").size(), 2u);
  EXPECT_EQ(j.at("runs")[1].at("threads"), 2);
  EXPECT_EQ(j.at("runs")[1].at("result_s"), 5.0);
  EXPECT_EQ(j.at("runs")[1].at("timings").at("stages")[1].at("name"), "final");
  ASSERT_EQ(j.at("scaling").size(), 1u);
  EXPECT_EQ(j.at("scaling")[0].at("base_threads"), 1);
  EXPECT_EQ(j.at("scaling")[0].at("total").at("efficiency"), 10.0 / 6.0 / 2.0);
  EXPECT_EQ(j.at("scaling")[0].at("stages")[0].at("name"), "model");
}

TEST(SpeedBenchmarkReport, WarnsOfABusyMachineAndOfARunStarvedOfItsProcessor)
{
  SpeedBenchmarkReport report = twoThreadReport();
  report.machine.logicalCpus = 2;
  report.machine.loadAverage = { 1.0, 1.0, 1.0 };
  report.loadAverageEnd = { 3.5, 2.0, 1.0 };
  const std::vector<std::string> warnings = report.warnings();
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0],
    "the machine was busy: a load average of 3.50 on 2 logical processors; the times include "
    "waiting for them, and the thread scaling says little");
  EXPECT_EQ(warnings[1],
    "6 frames, 1 thread: the run had the processor 75 % of its wall time (other processes took "
    "the rest)");
  // A quiet machine and a run with its processor: nothing to say.
  report.loadAverageEnd = { 0.5, 0.5, 0.5 };
  report.runs[0].userCpuS = report.runs[0].wallS;
  EXPECT_TRUE(report.warnings().empty());
  EXPECT_TRUE(report.toJson().at("warnings").empty());
}

TEST(MachineDescription, ReadsTheCpuModelAndTheLoadAverageFromProcTexts)
{
  EXPECT_EQ(MachineDescription::cpuModelFromCpuinfo(
              "processor\t: 0\nvendor_id\t: Test\nmodel name\t: Test CPU @ 2.0GHz \nflags\t: x\n"
              "model name\t: Other\n"),
    "Test CPU @ 2.0GHz");
  EXPECT_EQ(MachineDescription::cpuModelFromCpuinfo("processor\t: 0\n"), "");
  const std::array<double, 3> load =
    MachineDescription::loadAverageFromText("1.50 0.75 0.25 2/345 6789\n");
  EXPECT_EQ(load, (std::array<double, 3>{ 1.5, 0.75, 0.25 }));
  EXPECT_EQ(fixtures::errorMessageOf([] { MachineDescription::loadAverageFromText("busy"); }),
    "load average: expected three non-negative numbers, got 'busy'");
}

} // namespace
} // namespace vimlop
