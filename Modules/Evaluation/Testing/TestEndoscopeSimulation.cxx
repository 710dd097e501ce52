#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/EndoscopeSimulation.h>

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

using namespace vimlop;

TEST(EndoscopeSimulation, RendersFramesDepthAndATrackerAlongATube)
{
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeSimulationOptions o;
  o.frames = 3;
  std::vector<int> counted;
  const SimulatedVideo video = simulateEndoscopeVideo(model, o,
    [&](const std::string& what, int done, int total)
    {
      EXPECT_EQ(what, "simulate: frame");
      EXPECT_EQ(total, 3);
      counted.push_back(done);
      return true;
    });
  EXPECT_EQ(counted, (std::vector<int>{ 1, 2, 3 }));
  ASSERT_EQ(video.frames.size(), 3u);
  EXPECT_EQ(video.names[2], "frame002.png");
  EXPECT_EQ(video.frames[0].cols, 320);
  EXPECT_EQ(video.depth[0].widthPx, 320);
  EXPECT_DOUBLE_EQ(video.frameTimesS[1], 1.0 / 30.0);
  // The tracker follows the tip, within its noise.
  const std::optional<Eigen::Vector3d> tip = video.tracker.positionAt(video.frameTimesS[1]);
  ASSERT_TRUE(tip);
  EXPECT_LT((*tip - video.camerasCT[1].centre).norm(), 1.0);
}

TEST(EndoscopeSimulation, RefusesASequenceOfOneFrameAndStopsWhenCancelled)
{
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeSimulationOptions o;
  o.frames = 1;
  try
  {
    simulateEndoscopeVideo(model, o, EvaluationProgress());
    FAIL() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "a simulated sequence needs at least 2 frames");
  }
  o.frames = 2;
  try
  {
    simulateEndoscopeVideo(model, o, [](const std::string&, int, int) { return false; });
    FAIL() << "no cancellation";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "simulate: frame: cancelled");
  }
}
