#include <vimlop/Pipeline/StageTimings.h>

#include "ErrorMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace vimlop
{
namespace
{

std::vector<std::string> namesOf(const StageTimings& t)
{
  std::vector<std::string> names;
  for (const StageTimings::Stage& s : t.stages())
  {
    names.push_back(s.name);
  }
  return names;
}

TEST(StageTimings, KeepsTheStagesInTheOrderTheyRan)
{
  StageTimings t;
  t.set("frames", 0.5, 0.4);
  t.set("model", 2.0, 3.5);
  t.set("contours", 0.25, 0.25);
  EXPECT_EQ(namesOf(t), (std::vector<std::string>{ "frames", "model", "contours" }));
  EXPECT_DOUBLE_EQ(t.totalWallS(), 2.75);
  EXPECT_DOUBLE_EQ(t.totalCpuS(), 4.15);
  ASSERT_NE(t.find("model"), nullptr);
  EXPECT_DOUBLE_EQ(t.find("model")->cpuS, 3.5);
  EXPECT_EQ(t.find("sfm"), nullptr);
}

TEST(StageTimings, AStageRunAgainReplacesItsTimeInItsPlace)
{
  StageTimings t;
  t.set("frames", 0.5, 0.5);
  t.set("model", 2.0, 2.0);
  t.set("frames", 0.75, 1.0);
  EXPECT_EQ(namesOf(t), (std::vector<std::string>{ "frames", "model" }));
  EXPECT_DOUBLE_EQ(t.find("frames")->wallS, 0.75);
  t.remove("frames");
  t.remove("never-ran");
  EXPECT_EQ(namesOf(t), (std::vector<std::string>{ "model" }));
}

TEST(StageTimings, AppendingAddsTheOtherStagesAfterTheseOrInTheirPlace)
{
  StageTimings pipeline;
  pipeline.set("frames", 1.0, 1.0);
  pipeline.set("final", 4.0, 7.5);
  StageTimings outputs;
  outputs.set("video", 2.0, 2.0);
  outputs.set("frames", 3.0, 3.0);
  pipeline.append(outputs);
  EXPECT_EQ(namesOf(pipeline), (std::vector<std::string>{ "frames", "final", "video" }));
  EXPECT_DOUBLE_EQ(pipeline.find("frames")->wallS, 3.0);
}

TEST(StageTimings, RefusesANamelessStageAndNegativeOrNonFiniteTimes)
{
  StageTimings t;
  EXPECT_EQ(
    fixtures::errorMessageOf([&] { t.set("", 1.0, 1.0); }), "stage timings: a stage needs a name");
  EXPECT_EQ(fixtures::errorMessageOf([&] { t.set("sfm", -0.5, 1.0); }),
    "stage timings: stage 'sfm' has a negative or non-finite time (wall -0.5 s, CPU 1 s)");
  EXPECT_EQ(
    fixtures::errorMessageOf([&] { t.set("sfm", 1.0, std::numeric_limits<double>::quiet_NaN()); }),
    "stage timings: stage 'sfm' has a negative or non-finite time (wall 1 s, CPU nan s)");
  EXPECT_TRUE(t.empty());
}

TEST(StageTimings, ItsJsonKeepsTheOrderAndReadsBack)
{
  StageTimings t;
  t.set("sfm", 1.5, 2.5);
  t.set("data", 0.125, 0.125);
  const nlohmann::json j = t.toJson();
  ASSERT_EQ(j.at("stages").size(), 2u);
  EXPECT_EQ(j.at("stages")[0].at("name"), "sfm");
  EXPECT_DOUBLE_EQ(j.at("stages")[1].at("wall_s").get<double>(), 0.125);
  EXPECT_DOUBLE_EQ(j.at("total_wall_s").get<double>(), 1.625);
  EXPECT_DOUBLE_EQ(j.at("total_cpu_s").get<double>(), 2.625);
  const StageTimings back = StageTimings::fromJson(j, "summary");
  EXPECT_EQ(namesOf(back), namesOf(t));
  EXPECT_DOUBLE_EQ(back.find("sfm")->cpuS, 2.5);
}

TEST(StageTimings, JsonWithoutStagesOrWithABadStageIsRefusedNamingItsSource)
{
  EXPECT_EQ(fixtures::errorMessageOf(
              [] {
                StageTimings::fromJson(nlohmann::json{ { "total_wall_s", 1.0 } }, "out.json");
              }),
    "'out.json': stage timings: expected an object with a list \"stages\"");
  const nlohmann::json noCpu = { { "stages", { { { "name", "sfm" }, { "wall_s", 1.0 } } } } };
  EXPECT_EQ(fixtures::errorMessageOf([&] { StageTimings::fromJson(noCpu, "out.json"); }),
    "'out.json': stage timings: each stage needs a \"name\", \"wall_s\" and \"cpu_s\"");
  const nlohmann::json negative = { { "stages",
    { { { "name", "sfm" }, { "wall_s", -1.0 }, { "cpu_s", 1.0 } } } } };
  EXPECT_EQ(fixtures::errorMessageOf([&] { StageTimings::fromJson(negative, "out.json"); }),
    "'out.json': stage timings: stage 'sfm' has a negative or non-finite time (wall -1 s, CPU "
    "1 s)");
}

TEST(StageTimings, TheSummaryLineNamesEachStageInOrderWithTheTotals)
{
  StageTimings t;
  EXPECT_EQ(t.summaryLine(), "(total 0.00 s, CPU 0.00 s)");
  t.set("frames", 0.5, 0.25);
  t.set("model", 2.0, 4.0);
  EXPECT_EQ(t.summaryLine(), "frames 0.50 s, model 2.00 s (total 2.50 s, CPU 4.25 s)");
}

TEST(StageTimings, AMarkSaysWhenTheResultBecameUsableAndReadsBackFromJson)
{
  StageTimings t;
  t.set("final", 4.0, 7.5);
  EXPECT_FALSE(t.toJson().contains("marks")); // the layout of the runs before marks
  t.mark("result_usable", 4.25);
  t.set("video", 1.0, 1.0);
  EXPECT_EQ(t.summaryLine(),
    "final 4.00 s, video 1.00 s (total 5.00 s, CPU 8.50 s); result_usable at 4.25 s");
  // A mark set again moves; marks are not stages and add nothing to the totals.
  t.mark("result_usable", 4.5);
  ASSERT_EQ(t.marks().size(), 1u);
  EXPECT_DOUBLE_EQ(t.totalWallS(), 5.0);
  const nlohmann::json j = t.toJson();
  ASSERT_EQ(j.at("marks").size(), 1u);
  EXPECT_EQ(j.at("marks")[0].at("name"), "result_usable");
  const StageTimings back = StageTimings::fromJson(j, "summary");
  ASSERT_NE(back.findMark("result_usable"), nullptr);
  EXPECT_DOUBLE_EQ(back.findMark("result_usable")->atWallS, 4.5);
  EXPECT_EQ(back.findMark("never"), nullptr);
  StageTimings appended;
  appended.append(back);
  EXPECT_DOUBLE_EQ(appended.findMark("result_usable")->atWallS, 4.5);
}

TEST(StageTimings, RefusesANamelessOrNegativeMarkAndAMalformedListOfMarks)
{
  StageTimings t;
  EXPECT_EQ(
    fixtures::errorMessageOf([&] { t.mark("", 1.0); }), "stage timings: a mark needs a name");
  EXPECT_EQ(fixtures::errorMessageOf([&] { t.mark("result_usable", -1.0); }),
    "stage timings: mark 'result_usable' has a negative or non-finite time (-1 s)");
  const nlohmann::json notAList = { { "stages", nlohmann::json::array() }, { "marks", 3 } };
  EXPECT_EQ(fixtures::errorMessageOf([&] { StageTimings::fromJson(notAList, "out.json"); }),
    "'out.json': stage timings: \"marks\" must be a list");
  const nlohmann::json noTime = { { "stages", nlohmann::json::array() },
    { "marks", { { { "name", "result_usable" } } } } };
  EXPECT_EQ(fixtures::errorMessageOf([&] { StageTimings::fromJson(noTime, "out.json"); }),
    "'out.json': stage timings: each mark needs a \"name\" and \"at_wall_s\"");
}

TEST(StageTimings, AStopwatchCountsTheCpuTimeOfABusyLoop)
{
  const StageTimings::Stopwatch watch;
  // About 50 ms of arithmetic (the result is used, so it is not optimized away).
  volatile double sink = 0.0;
  while (watch.cpuS() < 0.05 && watch.wallS() < 10.0)
  {
    for (int i = 0; i < 10000; ++i)
    {
      sink = sink + std::sqrt(static_cast<double>(i));
    }
  }
  StageTimings t;
  t.set("loop", watch);
  EXPECT_GE(t.find("loop")->cpuS, 0.05);
  // One thread: the wall time is at least most of the CPU time.
  EXPECT_GE(t.find("loop")->wallS, 0.9 * t.find("loop")->cpuS);
  EXPECT_GT(sink, 0.0);
}

} // namespace
} // namespace vimlop
