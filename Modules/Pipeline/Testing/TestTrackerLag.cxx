#include <vimlop/Pipeline/TrackerLag.h>

#include "ErrorMessage.h"
#include <vimlop/Pipeline/EndoscopeTracker.h>
#include <vimlop/Pipeline/TrackerRecording.h>
#include <vimlop/Video/TrackerTrajectory.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <functional>
#include <random>

namespace vimlop
{
namespace
{

constexpr double fps = 30.0;

/// A scope going back and forth along a curve, 10 mm each way every 4 s
/// (at most 16 mm/s, slow to a stop at each end), in the CT.
Eigen::Vector3d backAndForth(double tS)
{
  const double s = 10.0 * std::sin(2.0 * M_PI * tS / 4.0);
  return Eigen::Vector3d(s, 0.3 * s, 40.0 + 0.02 * s * s);
}

/// A scope moving at one speed, 5 mm/s along x.
Eigen::Vector3d oneSpeed(double tS)
{
  return Eigen::Vector3d(5.0 * tS, 1.0, 40.0);
}

/// The tracker's registration to the CT: turned and shifted.
Eigen::Matrix4d trackerToCT()
{
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() =
    Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  m.topRightCorner<3, 1>() = Eigen::Vector3d(-20.0, 35.0, 110.0);
  return m;
}

/// A 40 Hz tracker over `seconds` that reports where the tip was `lagS`
/// earlier, 0.5 mm off (its registration's error), with 0.2 mm of noise per
/// axis, in its own frame.
TrackerTrajectory recordingOf(
  const std::function<Eigen::Vector3d(double)>& path, double lagS, double seconds)
{
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.2);
  const Eigen::Matrix4d fromCT = trackerToCT().inverse();
  std::vector<TrackerTrajectory::Sample> samples;
  for (double t = -1.0; t <= seconds + 1.0; t += 1.0 / 40.0)
  {
    const Eigen::Vector3d tipCT = path(t - lagS) + Eigen::Vector3d(0.3, -0.4, 0.0) +
      Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    samples.push_back({ t, (fromCT * tipCT.homogeneous()).head<3>() });
  }
  return TrackerTrajectory(std::move(samples));
}

TEST(TrackerLag, FindsTheLagOfATrackerThatReportsLateFromTheVideosMotion)
{
  // 10 s of video that drifts 0.5 mm/s from the scope, and jumps 3 mm at
  // 5 s (a pose recast from the tracker), against a tracker 60 ms late: the
  // lag is found within 5 ms (each pair's displacements carry about 0.4 mm
  // of the tracker's noise against a change of speed of up to 23 mm/s over
  // the span: 17 ms a pair, over 270 overlapping pairs), and taking it off
  // leaves the noise and the drift, where reading at the frames' times
  // leaves the motion over 60 ms too.
  const TrackerTrajectory recording = recordingOf(backAndForth, 0.06, 10.0);
  std::deque<double> times;
  std::deque<Eigen::Vector3d> centres;
  for (int f = 0; f < 300; ++f)
  {
    const double t = f / fps;
    times.push_back(t);
    centres.push_back(backAndForth(t) + Eigen::Vector3d(0.5 * t, 0.0, t < 5.0 ? 0.0 : 3.0));
  }
  const std::optional<TrackerLagEstimate> e =
    TrackerLag::fit(recording, trackerToCT(), times, centres, TrackerLagOptions());
  ASSERT_TRUE(e);
  EXPECT_NEAR(e->lagS, 0.06, 0.005);
  EXPECT_LT(e->disagreementMm, 0.75 * e->disagreementAtZeroMm);
  // A frame the recording does not cover at every lag tried makes no pair.
  times.push_front(-0.9);
  centres.push_front(backAndForth(-0.9));
  EXPECT_EQ(TrackerLag::fit(recording, trackerToCT(), times, centres, TrackerLagOptions())->pairs,
    e->pairs);
  // Nor do frames further apart than twice the span: every other second.
  std::deque<double> sparseTimes;
  std::deque<Eigen::Vector3d> sparseCentres;
  for (int f = 0; f < 300; f += 30)
  {
    sparseTimes.push_back(f / fps);
    sparseCentres.push_back(backAndForth(f / fps));
  }
  EXPECT_FALSE(
    TrackerLag::fit(recording, trackerToCT(), sparseTimes, sparseCentres, TrackerLagOptions()));
}

TEST(TrackerLag, ShowsNoLagForAScopeThatKeepsOneSpeed)
{
  // At one speed a late tracker is only shifted, which is its offset's
  // business: no lag is found.
  const TrackerTrajectory recording = recordingOf(oneSpeed, 0.06, 10.0);
  std::deque<double> times;
  std::deque<Eigen::Vector3d> centres;
  for (int f = 0; f < 300; ++f)
  {
    times.push_back(f / fps);
    centres.push_back(oneSpeed(f / fps));
  }
  EXPECT_FALSE(TrackerLag::fit(recording, trackerToCT(), times, centres, TrackerLagOptions()));
}

TEST(TrackerLag, ReadsTheTrackerLaterOnceEnoughFramesTrackedAgainstTheCTShowItsLag)
{
  const TrackerTrajectory recording = recordingOf(backAndForth, 0.06, 10.0);
  TrackerLagOptions options;
  TrackerLag lag(recording, trackerToCT(), options);
  auto frameAt = [](int f, TrackingState state)
  {
    TrackedFrame t;
    t.cameraToCT.centre = backAndForth(f / fps);
    t.state = state;
    return t;
  };
  // Lost frames teach nothing, however many.
  for (int f = 0; f < 200; ++f)
  {
    lag.learn(f / fps, frameAt(f, TrackingState::Lost));
  }
  EXPECT_EQ(lag.lagS(), 0.0);
  EXPECT_FALSE(lag.estimate());
  // Degraded frames do: their motion is the scope's, even off the CT. The
  // first estimate waits for enough pairs of frames.
  int f = 0;
  for (; !lag.estimate() && f < 300; ++f)
  {
    lag.learn(f / fps, frameAt(f, f % 2 ? TrackingState::Tracking : TrackingState::Degraded));
  }
  ASSERT_TRUE(lag.estimate());
  EXPECT_GE(lag.estimate()->pairs, options.minPairs);
  EXPECT_LT(f, 2 * options.minPairs);
  EXPECT_NEAR(lag.lagS(), 0.06, 0.005);
  // The recording is now read that much later: over a quick stretch (10-16
  // mm/s, where 60 ms is 0.6-1 mm) its tip is where the scope is, up to the
  // tracker's offset and noise.
  const Eigen::Vector3d offset(0.3, -0.4, 0.0);
  double lateMm = 0.0, readLaterMm = 0.0;
  for (int g = 165; g < 195; ++g)
  {
    const Eigen::Vector3d at = backAndForth(g / fps) + offset;
    lateMm += (trackerPriorAt(recording, trackerToCT(), g / fps)->tipCT - at).norm() / 30.0;
    readLaterMm += (lag.priorAt(g / fps)->tipCT - at).norm() / 30.0;
  }
  EXPECT_GT(lateMm, 0.7);
  EXPECT_LT(readLaterMm, 0.4);

  // Switched off, nothing is learned.
  TrackerLagOptions off;
  off.maxLagS = 0.0;
  TrackerLag none(recording, trackerToCT(), off);
  for (int g = 0; g < 300; ++g)
  {
    none.learn(g / fps, frameAt(g, TrackingState::Tracking));
  }
  EXPECT_EQ(none.lagS(), 0.0);
}

TEST(TrackerLag, RefusesSettingsThatCannotMakeAnEstimate)
{
  const TrackerTrajectory recording = recordingOf(backAndForth, 0.0, 2.0);
  auto messageWith = [&](const std::function<void(TrackerLagOptions&)>& set)
  {
    TrackerLagOptions o;
    set(o);
    return fixtures::errorMessageOf([&] { TrackerLag(recording, trackerToCT(), o); });
  };
  EXPECT_EQ(messageWith([](TrackerLagOptions& o) { o.maxLagS = -0.1; }),
    "tracker lag: the largest lag searched must lie in [0, 2] s, not -0.1");
  EXPECT_EQ(messageWith([](TrackerLagOptions& o) { o.maxLagS = 0.005; }),
    "tracker lag: the largest lag searched must be 0 or at least two steps, not 0.005");
  EXPECT_EQ(messageWith([](TrackerLagOptions& o) { o.stepS = 0.0; }),
    "tracker lag: the search's step must be positive (s), not 0");
  EXPECT_EQ(messageWith([](TrackerLagOptions& o) { o.spanS = 0.0; }),
    "tracker lag: the displacements' span must lie in (0, 10] s, not 0");
  EXPECT_EQ(messageWith([](TrackerLagOptions& o) { o.minPairs = 5; }),
    "tracker lag: an estimate needs at least 10 pairs of frames, not 5");
  EXPECT_EQ(messageWith([](TrackerLagOptions& o) { o.windowFrames = 20; }),
    "tracker lag: the window must hold at least the pairs an estimate needs, not 20");
}

} // namespace
} // namespace vimlop
