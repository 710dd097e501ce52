#include <vimlop/Core/PathReplay.h>

#include "ErrorMessage.h"
#include <vimlop/Core/RegistrationMetrics.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

using namespace vimlop;

TEST(PathReplay, GoesForwardAndBackWithPausesAndFastMovesAndStaysOnThePath)
{
  PathReplayOptions o;
  o.pathFrames = 40;
  const std::vector<double> at = replayPositions(600, o, 3);
  ASSERT_EQ(at.size(), 600u);
  EXPECT_EQ(at[0], 0.0);
  int still = 0, forward = 0, back = 0, fast = 0;
  for (std::size_t f = 1; f < at.size(); ++f)
  {
    EXPECT_GE(at[f], 0.0);
    EXPECT_LE(at[f], 39.0);
    const double step = at[f] - at[f - 1];
    // A step is 0, 1 or the fast speed, or shorter where it turned at an end.
    EXPECT_LE(std::abs(step), o.fastSpeed + 1e-12) << f;
    still += step == 0.0;
    forward += step > 0.0;
    back += step < 0.0;
    fast += std::abs(step) > 1.0 + 1e-12;
  }
  EXPECT_GT(still, 30);
  EXPECT_GT(forward, 150);
  EXPECT_GT(back, 150);
  EXPECT_GT(fast, 20);
  // The same seed, the same sequence; another seed, another.
  EXPECT_EQ(replayPositions(600, o, 3), at);
  EXPECT_NE(replayPositions(600, o, 4), at);
}

TEST(PathReplay, LeadsStraightIntoThePassageFirst)
{
  PathReplayOptions o;
  o.pathFrames = 40;
  o.leadFrames = 30;
  const std::vector<double> at = replayPositions(100, o, 3);
  for (int f = 0; f < 30; ++f)
  {
    EXPECT_EQ(at[static_cast<std::size_t>(f)], f);
  }
  o.leadFrames = 40;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "path replay: 40 lead frames do not fit a path of 40 poses");
}

TEST(PathReplay, InterpolatesPosesBetweenNeighbours)
{
  // A path along x that turns about z by 1 degree per pose.
  std::vector<CameraPose> path(10);
  for (int i = 0; i < 10; ++i)
  {
    path[static_cast<std::size_t>(i)].centre = { 0.5 * i, 0.0, 0.0 };
    path[static_cast<std::size_t>(i)].rotation =
      Eigen::AngleAxisd(i * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  PathReplayOptions o;
  o.pathFrames = 10;
  o.pauseShare = 0.0;
  o.fastShare = 1.0;
  o.fastSpeed = 1.5;
  const std::vector<CameraPose> poses = replayPath(path, 50, o, 1);
  const std::vector<double> at = replayPositions(50, o, 1);
  ASSERT_EQ(poses.size(), 50u);
  for (std::size_t f = 0; f < poses.size(); ++f)
  {
    EXPECT_NEAR(poses[f].centre.x(), 0.5 * at[f], 1e-12) << f;
    CameraPose expected;
    expected.rotation =
      Eigen::AngleAxisd(at[f] * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_LT(cameraAngleErrorDeg(poses[f], expected), 1e-9) << f;
  }
}

TEST(PathReplay, RefusesOptionsOutOfRangeAndAPathOfAnotherLength)
{
  PathReplayOptions o;
  EXPECT_EQ(fixtures::errorMessageOf([&] { replayPositions(10, o, 1); }),
    "path replay: no path length given");
  o.pathFrames = 1;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "path replay: the path needs at least 2 poses, not 1");
  o.pathFrames = 10;
  o.pauseShare = 0.7;
  o.fastShare = 0.5;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "path replay: the shares of pauses (0.7) and fast moves (0.5) must not be negative nor add up "
    "to more than 1");
  o = {};
  o.pathFrames = 10;
  o.maxSegmentFrames = 5;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "path replay: segments of 15 to 5 frames are not a range");
  o = {};
  o.pathFrames = 10;
  EXPECT_EQ(fixtures::errorMessageOf([&] { replayPath(std::vector<CameraPose>(4), 10, o, 1); }),
    "path replay: a path of 4 poses, but 10 were asked for");
  EXPECT_EQ(fixtures::errorMessageOf([&] { replayPositions(0, o, 1); }),
    "path replay: at least 1 frame, not 0");
}
