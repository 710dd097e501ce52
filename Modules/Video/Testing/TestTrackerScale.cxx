#include <vimlop/Core/Error.h>
#include <vimlop/Video/TrackerScale.h>
#include <vimlop/Video/TrackerTrajectory.h>
#include <vimlop/Video/VideoInput.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <fstream>
#include <limits>
#include <random>

using namespace vimlop;

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;

/// A tip moving 15 mm/s along a gentle curve, in mm, at time t (s).
Eigen::Vector3d tip(double t)
{
  return { 15.0 * t, 2.0 * std::sin(3.0 * t), 0.5 * t * t };
}

/// Tracker samples at `rateHz` over [t0, t1] with Gaussian noise.
TrackerTrajectory tracker(double t0, double t1, double rateHz, double noiseMm, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noiseMm);
  std::vector<TrackerTrajectory::Sample> samples;
  for (double t = t0; t <= t1 + 1e-9; t += 1.0 / rateHz)
  {
    samples.push_back({ t, tip(t) + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)) });
  }
  return TrackerTrajectory(samples);
}

/// 30 frames at 30 fps from t = 0, their centres in an SfM frame that is the
/// tip's path rotated, shifted and scaled by 1 / `mmPerUnit`.
void frames(double mmPerUnit, std::vector<double>& times, std::vector<Eigen::Vector3d>& centres)
{
  const Eigen::Matrix3d r =
    Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  for (int f = 0; f < 30; ++f)
  {
    times.push_back(f / 30.0);
    centres.push_back(r * tip(times.back()) / mmPerUnit + Eigen::Vector3d(3, -2, 1));
  }
}

std::string csv(const std::string& name, const std::string& text)
{
  const std::string path = out + "/" + name;
  std::ofstream(path) << text;
  return path;
}

template <typename F>
std::string messageOf(F&& f)
{
  try
  {
    f();
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(TrackerScale, ScalesSfMToTheTrackedLength)
{
  std::vector<double> times;
  std::vector<Eigen::Vector3d> centres;
  frames(0.5, times, centres);
  // A noisy tracker (0.2 mm at 40 Hz) that starts before and ends after the video.
  const TrackerScaleResult result =
    estimateTrackerScale(tracker(-0.3, 1.3, 40.0, 0.2, 1), times, centres);
  EXPECT_NEAR(result.scale, 0.5, 0.5 * 0.02);
  EXPECT_EQ(result.framesUsed.size(), 30u);
  EXPECT_TRUE(result.framesDropped.empty());
  EXPECT_TRUE(result.warnings.empty());
  // Summing every frame's noisy step instead would overestimate the length.
  TrackerScaleOptions everyFrame;
  everyFrame.minChordMm = 0.0;
  everyFrame.smoothingS = 0.0;
  EXPECT_GT(
    estimateTrackerScale(tracker(-0.3, 1.3, 40.0, 0.2, 1), times, centres, everyFrame).scale, 0.55);
}

TEST(TrackerScale, ATrackerGlitchIsDroppedWithAWarningAndLeavesTheScale)
{
  std::vector<double> times;
  std::vector<Eigen::Vector3d> centres;
  frames(0.5, times, centres);
  std::vector<TrackerTrajectory::Sample> samples = tracker(-0.3, 1.3, 40.0, 0.2, 1).samples();
  const TrackerTrajectory clean(samples);
  EXPECT_EQ(clean.samples().size(), samples.size()); // no clean sample is taken for a glitch
  // One sample a metre off, and two neighbours 300 mm off.
  samples[20].positionMm.x() += 1000.0;
  samples[30].positionMm.y() -= 300.0;
  samples[31].positionMm.y() -= 300.0;
  std::vector<std::string> warnings;
  const TrackerTrajectory glitchy(samples, &warnings);
  EXPECT_EQ(glitchy.samples().size(), samples.size() - 3);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
    "dropped 3 tracker sample(s) far from the samples around them, a glitch of the tracker? (at "
    "0.200 s, 0.450 s, 0.475 s)");
  EXPECT_NEAR(estimateTrackerScale(glitchy, times, centres).scale,
    estimateTrackerScale(clean, times, centres).scale, 0.5 * 0.01);
}

TEST(TrackerScale, DropsFramesOutsideTheRecordingAndUnregisteredOnes)
{
  std::vector<double> times;
  std::vector<Eigen::Vector3d> centres;
  frames(2.0, times, centres);
  centres[3] = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  // The tracker stops at 0.475 s: frames 15-29 (from 0.5 s) lie outside it.
  const TrackerScaleResult result =
    estimateTrackerScale(tracker(-0.2, 0.49, 40.0, 0.0, 2), times, centres);
  EXPECT_NEAR(result.scale, 2.0, 2.0 * 0.02);
  EXPECT_EQ(result.framesUsed.size(), 14u);
  EXPECT_EQ(result.framesDropped.size(), 16u);
  ASSERT_EQ(result.warnings.size(), 2u);
  EXPECT_EQ(result.warnings[0].rfind(
              "tracker scale: dropped 15 frame(s) outside the tracker's time span", 0),
    0u)
    << result.warnings[0];
  EXPECT_EQ(result.warnings[1], "tracker scale: dropped 1 frame(s) that SfM did not register");
}

TEST(TrackerScale, FailsWithoutTimeOverlapOrMotion)
{
  std::vector<double> times;
  std::vector<Eigen::Vector3d> centres;
  frames(1.0, times, centres);
  EXPECT_EQ(
    messageOf([&] { estimateTrackerScale(tracker(5.0, 6.0, 40.0, 0.0, 3), times, centres); }),
    "tracker scale: the tracker and the frames do not overlap in time (tracker 5.000..6.000 s, "
    "frames 0.000..0.967 s)");
  std::vector<Eigen::Vector3d> still(30, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(
    messageOf([&] { estimateTrackerScale(tracker(-0.2, 1.2, 40.0, 0.0, 3), times, still); }),
    "tracker scale: the SfM trajectory has no length (the endoscope did not move)");
}

TEST(TrackerScale, ATrackerInMetresIsRefusedWithTheUnitNamed)
{
  std::vector<double> times;
  std::vector<Eigen::Vector3d> centres;
  frames(0.5, times, centres);
  std::vector<TrackerTrajectory::Sample> metres;
  for (double t = -0.2; t <= 1.2; t += 1.0 / 40.0)
  {
    metres.push_back({ t, tip(t) / 1000.0 });
  }
  const std::string message =
    messageOf([&] { estimateTrackerScale(TrackerTrajectory(metres), times, centres); });
  EXPECT_EQ(message.rfind("tracker scale: the tracked trajectory is only 0.014", 0), 0u) << message;
  EXPECT_NE(message.find("mm long over 30 frames, too short for a scale: are the tracker's "
                         "positions in metres? They are read as mm (or give the initial scale)"),
    std::string::npos)
    << message;
}

TEST(TrackerTrajectory, SmoothingFollowsTheTipToTheEnds)
{
  // A local line fit, unlike a moving average, does not lag at the ends.
  const TrackerTrajectory t = tracker(0.0, 1.0, 40.0, 0.0, 4);
  EXPECT_LT((*t.positionAt(1.0, 0.1) - tip(1.0)).norm(), 0.1);
  EXPECT_LT((*t.positionAt(0.0, 0.1) - tip(0.0)).norm(), 0.1);
  EXPECT_LT((*t.positionAt(0.4321, 0.0) - tip(0.4321)).norm(), 0.05);
  EXPECT_FALSE(t.positionAt(1.01).has_value());
  EXPECT_FALSE(t.positionAt(-0.01).has_value());
}

TEST(TrackerTrajectory, ReadsCsvAndWarnsAboutWhatItDrops)
{
  const std::string path = csv("tracker-good.csv",
    "# EM tracker export\n"
    "timestamp,x,y,z,qw,qx,qy,qz\n"
    "0.0,1,2,3,1,0,0,0\n"
    "0.1,1.5,2,3,1,0,0,0\n"
    "0.2,oops,2,3,1,0,0,0\n"
    "\n"
    "0.15,1.2,2,3,1,0,0,0\n"
    "0.1,9,9,9,1,0,0,0\n"
    "0.3,2.5,2,3\n");
  std::vector<std::string> warnings;
  const TrackerTrajectory t = TrackerTrajectory::readCsv(path, &warnings);
  ASSERT_EQ(t.samples().size(), 3u);
  EXPECT_EQ(t.samples()[2].timeS, 0.15);                            // sorted by time
  EXPECT_EQ(t.samples()[1].positionMm, Eigen::Vector3d(1.5, 2, 3)); // the first of two at 0.1 s
  // The last row has no rotation in a file whose header promises one.
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0], "'" + path + "': dropped 2 malformed row(s) (line 5, 9)");
  EXPECT_EQ(warnings[1], "dropped 1 tracker sample(s) with a timestamp already seen");
  // Round trip.
  t.writeCsv(out + "/tracker-written.csv");
  const TrackerTrajectory again = TrackerTrajectory::readCsv(out + "/tracker-written.csv");
  ASSERT_EQ(again.samples().size(), 3u);
  ASSERT_TRUE(again.samples()[0].rotation.has_value());
  EXPECT_TRUE(again.samples()[0].rotation->isIdentity(0.0));
}

TEST(TrackerTrajectory, ReadsASixDofSensorsRotationFromQuaternionColumns)
{
  // A sensor turning 90 degrees about z in a second; a quaternion written
  // with three digits (length 0.9995) is taken, one of length 0.5 is no
  // rotation and its row is dropped.
  const std::string path = csv("tracker-6dof.csv",
    "time_s,x_mm,y_mm,z_mm,qw,qx,qy,qz\n"
    "0.0,0,0,0,1,0,0,0\n"
    "0.5,1,0,0,0.5,0,0,0\n"
    "1.0,2,0,0,0.707,0,0,0.707\n");
  std::vector<std::string> warnings;
  const TrackerTrajectory t = TrackerTrajectory::readCsv(path, &warnings);
  ASSERT_EQ(t.samples().size(), 2u);
  EXPECT_TRUE(t.hasRotations());
  EXPECT_EQ(
    warnings, std::vector<std::string>{ "'" + path + "': dropped 1 malformed row(s) (line 3)" });
  const std::optional<Eigen::Matrix4d> halfway = t.poseAt(0.5);
  ASSERT_TRUE(halfway.has_value());
  const Eigen::Matrix3d expected = Eigen::AngleAxisd(M_PI / 4.0, Eigen::Vector3d::UnitZ()).matrix();
  EXPECT_LT((halfway->topLeftCorner<3, 3>() - expected).norm(), 1e-9);
  EXPECT_LT((halfway->topRightCorner<3, 1>() - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);

  // The written file reads back the same rotations, to every digit.
  t.writeCsv(out + "/tracker-6dof-written.csv");
  const TrackerTrajectory again = TrackerTrajectory::readCsv(out + "/tracker-6dof-written.csv");
  ASSERT_EQ(again.samples().size(), 2u);
  EXPECT_LT((*again.samples()[1].rotation - *t.samples()[1].rotation).norm(), 1e-12);

  // A position-only file has no pose.
  const std::string positions =
    csv("tracker-positions.csv", "time_s,x_mm,y_mm,z_mm\n0,0,0,0\n1,2,0,0\n");
  EXPECT_FALSE(TrackerTrajectory::readCsv(positions).poseAt(0.5).has_value());
  EXPECT_FALSE(TrackerTrajectory::readCsv(positions).hasRotations());
}

TEST(TrackerTrajectory, BadFilesAreNamedWithTheProblem)
{
  EXPECT_EQ(messageOf([] { TrackerTrajectory::readCsv(out + "/no-tracker.csv"); }),
    "'" + out + "/no-tracker.csv': no such file or not readable");
  const std::string one = csv("tracker-one-row.csv", "time_s,x_mm,y_mm,z_mm\n0.0,1,2,3\n");
  EXPECT_EQ(messageOf([&] { TrackerTrajectory::readCsv(one); }),
    "'" + one + "': too few tracker rows: 1 usable, at least 2 needed");
  const std::string noColumn = csv("tracker-no-z.csv", "time_s,x_mm,y_mm\n0.0,1,2\n");
  EXPECT_EQ(messageOf([&] { TrackerTrajectory::readCsv(noColumn); }),
    "'" + noColumn + "': no column 'z_mm' in the header (expected time_s,x_mm,y_mm,z_mm)");
  const std::string someRotation =
    csv("tracker-no-qz.csv", "time_s,x_mm,y_mm,z_mm,qw,qx,qy\n0,1,2,3,1,0,0\n1,1,2,3,1,0,0\n");
  EXPECT_EQ(messageOf([&] { TrackerTrajectory::readCsv(someRotation); }),
    "'" + someRotation +
      "': the header has only 3 of the rotation's columns qw,qx,qy,qz (all four or none)");
  const std::string empty = csv("tracker-empty.csv", "");
  EXPECT_EQ(messageOf([&] { TrackerTrajectory::readCsv(empty); }),
    "'" + empty + "': the file is empty (expected a header: time_s,x_mm,y_mm,z_mm)");
}

TEST(TrackerScale, FrameTimesFollowTheFrameIdsFromTheFirstFrame)
{
  // Frames 1, 2 and 4 of a 25 fps video (frame 3's file is missing): the
  // first frame is at the offset, frame 4 three frames later, not two.
  const std::vector<double> times = frameTimesS({ 1, 2, 4 }, 25.0, 10.0);
  ASSERT_EQ(times.size(), 3u);
  EXPECT_DOUBLE_EQ(times[0], 10.0);
  EXPECT_DOUBLE_EQ(times[1], 10.04);
  EXPECT_DOUBLE_EQ(times[2], 10.12);
}
