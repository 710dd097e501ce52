#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/EndoscopeSimulation.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

using namespace vimlop;

TEST(SimulatedVideo, MeasuresItsPathAndItsLeastDistanceToTheWall)
{
  SimulatedVideo video;
  EXPECT_EQ(video.pathLengthMm(), 0.0);
  for (const Eigen::Vector3d& centre :
    { Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 0, 0), Eigen::Vector3d(3, 4, 0) })
  {
    CameraPose camera;
    camera.centre = centre;
    video.camerasCT.push_back(camera);
  }
  EXPECT_DOUBLE_EQ(video.pathLengthMm(), 7.0);

  // Inside a sphere of radius 20 mm: the camera 5 mm from the centre is the closest to the wall.
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeSphere(20.0, 4));
  EXPECT_NEAR(video.leastWallDistanceMm(model), 15.0, 0.2);
  EXPECT_TRUE(std::isinf(SimulatedVideo().leastWallDistanceMm(model)));
}

namespace
{

/// Ten cameras 1 mm apart along x, one per frame at 30 frames per second: 30 mm/s.
std::vector<CameraPose> straightPath()
{
  std::vector<CameraPose> cameras(10);
  for (int f = 0; f < 10; ++f)
  {
    cameras[f].centre = Eigen::Vector3d(f, 0.0, 0.0);
  }
  return cameras;
}

std::string validationMessage(const EndoscopeSimulationOptions& o)
{
  try
  {
    o.validate();
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(SimulatedVideo, TrackerLatencyAndClockOffsetShiftTheRecordedTrajectoryInTime)
{
  EndoscopeSimulationOptions o;
  o.trackerNoiseMm = 0.0;
  const TrackerTrajectory ideal = simulateTrackerRecording(straightPath(), o);
  o.trackerLatencyS = 0.05;
  const TrackerTrajectory late = simulateTrackerRecording(straightPath(), o);
  o.trackerLatencyS = 0.03;
  o.trackerClockOffsetS = 0.02;
  const TrackerTrajectory lateAndOffset = simulateTrackerRecording(straightPath(), o);

  // The same time stamps; each sample reports where the tip was 50 ms earlier.
  ASSERT_EQ(late.samples().size(), ideal.samples().size());
  for (size_t i = 0; i < late.samples().size(); ++i)
  {
    const double t = late.samples()[i].timeS;
    EXPECT_DOUBLE_EQ(t, ideal.samples()[i].timeS);
    const std::optional<Eigen::Vector3d> before = ideal.positionAt(t - 0.05);
    if (before)
    {
      EXPECT_NEAR((late.samples()[i].positionMm - *before).norm(), 0.0, 1e-9) << t;
    }
    // At 30 mm/s, 50 ms is 1.5 mm behind the tip.
    EXPECT_NEAR(ideal.samples()[i].positionMm.x() - late.samples()[i].positionMm.x(), 1.5, 1e-9);
    EXPECT_NEAR(
      (lateAndOffset.samples()[i].positionMm - late.samples()[i].positionMm).norm(), 0.0, 1e-9);
  }
}

TEST(SimulatedVideo, ASixDofTrackerRecordsTheCamerasRotationWithItsNoise)
{
  // The camera turns 2 degrees a frame about the view axis along the
  // straight path: the recorded rotation follows it, between frames too,
  // within the noise; without noise, exactly. The positions are the same
  // with the rotation on or off.
  std::vector<CameraPose> cameras = straightPath();
  for (std::size_t f = 0; f < cameras.size(); ++f)
  {
    cameras[f].rotation =
      Eigen::AngleAxisd(2.0 * f * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  EndoscopeSimulationOptions o;
  const TrackerTrajectory positions = simulateTrackerRecording(cameras, o);
  EXPECT_FALSE(positions.samples()[0].rotation.has_value());
  o.trackerRotation = true;
  o.trackerRotationNoiseDeg = 0.0;
  const TrackerTrajectory exact = simulateTrackerRecording(cameras, o);
  o.trackerRotationNoiseDeg = 0.3;
  const TrackerTrajectory noisy = simulateTrackerRecording(cameras, o);
  ASSERT_EQ(noisy.samples().size(), positions.samples().size());
  double sumSquaredDeg = 0.0;
  int inside = 0;
  for (std::size_t i = 0; i < noisy.samples().size(); ++i)
  {
    const TrackerTrajectory::Sample& n = noisy.samples()[i];
    EXPECT_EQ(n.positionMm, positions.samples()[i].positionMm);
    ASSERT_TRUE(n.rotation.has_value());
    const double frame = n.timeS * o.framesPerSecond;
    if (frame < 0.0 || frame > 9.0)
    {
      continue;
    }
    // 2 degrees a frame about z, at the sample's time.
    const Eigen::Matrix3d truth =
      Eigen::AngleAxisd(2.0 * frame * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_LT(Eigen::AngleAxisd(*exact.samples()[i].rotation * truth.transpose()).angle(), 1e-9);
    const double deg = Eigen::AngleAxisd(*n.rotation * truth.transpose()).angle() * 180.0 / M_PI;
    sumSquaredDeg += deg * deg;
    ++inside;
  }
  // The angle of a rotation vector with 0.3 degrees per axis: 0.52 degrees RMS.
  ASSERT_GT(inside, 10);
  EXPECT_NEAR(std::sqrt(sumSquaredDeg / inside), 0.3 * std::sqrt(3.0), 0.15);
  o.trackerRotationNoiseDeg = -1.0;
  EXPECT_EQ(validationMessage(o),
    "the tracker's rotation noise must be a finite number >= 0 degrees, not -1");
}

TEST(SimulatedVideo, ATrackerRegisteredWithAnErrorCarriesTheSameShiftAndTurnInEverySample)
{
  // The navigation system's error: every tip 1.5 mm off in one direction,
  // every rotation 2 degrees off about one axis, the same for all samples.
  std::vector<CameraPose> cameras = straightPath();
  for (std::size_t f = 0; f < cameras.size(); ++f)
  {
    cameras[f].rotation =
      Eigen::AngleAxisd(3.0 * f * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  }
  EndoscopeSimulationOptions o;
  o.trackerNoiseMm = 0.0;
  o.trackerRotation = true;
  o.trackerRotationNoiseDeg = 0.0;
  const TrackerTrajectory exact = simulateTrackerRecording(cameras, o);
  o.trackerPositionBiasMm = 1.5;
  o.trackerRotationBiasDeg = 2.0;
  const TrackerTrajectory biased = simulateTrackerRecording(cameras, o);
  ASSERT_EQ(biased.samples().size(), exact.samples().size());
  const Eigen::Vector3d shift = biased.samples()[0].positionMm - exact.samples()[0].positionMm;
  const Eigen::Matrix3d turn =
    *biased.samples()[0].rotation * exact.samples()[0].rotation->transpose();
  EXPECT_NEAR(shift.norm(), 1.5, 1e-9);
  EXPECT_NEAR(Eigen::AngleAxisd(turn).angle() * 180.0 / M_PI, 2.0, 1e-9);
  for (std::size_t i = 1; i < biased.samples().size(); ++i)
  {
    EXPECT_LT(
      (biased.samples()[i].positionMm - exact.samples()[i].positionMm - shift).norm(), 1e-9);
    EXPECT_LT((*biased.samples()[i].rotation - turn * *exact.samples()[i].rotation).norm(), 1e-9);
  }
  o.trackerPositionBiasMm = -1.0;
  EXPECT_EQ(
    validationMessage(o), "the tracker's position bias must be a finite number >= 0 mm, not -1");
  o.trackerPositionBiasMm = 0.0;
  o.trackerRotationBiasDeg = std::nan("");
  EXPECT_EQ(validationMessage(o),
    "the tracker's rotation bias must be a finite number >= 0 degrees, not nan");
}

TEST(SimulatedVideo, TheDefaultWorldIsIdealAndEachErrorSourceMakesItReal)
{
  EXPECT_TRUE(EndoscopeSimulationOptions().isIdealWorld());
  EXPECT_EQ(validationMessage(EndoscopeSimulationOptions()), "no error");
  auto real = [](auto change)
  {
    EndoscopeSimulationOptions o;
    change(o);
    return !o.isIdealWorld();
  };
  EXPECT_TRUE(real([](EndoscopeSimulationOptions& o) { o.fieldStop.radiusFraction = 0.6; }));
  EXPECT_TRUE(real([](EndoscopeSimulationOptions& o) { o.fieldStop.vignettingStrength = 0.3; }));
  EXPECT_TRUE(real([](EndoscopeSimulationOptions& o)
    { o.intrinsics.distortion = Eigen::Vector4d(-0.3, 0.0, 0.0, 0.0); }));
  EXPECT_TRUE(real([](EndoscopeSimulationOptions& o) { o.calibrationFocalErrorRelative = 0.01; }));
  EXPECT_TRUE(real([](EndoscopeSimulationOptions& o)
    { o.calibrationPrincipalPointErrorPx = Eigen::Vector2d(0.0, 2.0); }));
  EXPECT_TRUE(real([](EndoscopeSimulationOptions& o) { o.trackerLatencyS = 0.02; }));
  EXPECT_TRUE(real([](EndoscopeSimulationOptions& o) { o.trackerClockOffsetS = -0.1; }));
  EXPECT_TRUE(real([](EndoscopeSimulationOptions& o) { o.trackerPositionBiasMm = 1.0; }));
  EXPECT_TRUE(real([](EndoscopeSimulationOptions& o) { o.trackerRotationBiasDeg = 1.0; }));
  EXPECT_TRUE(
    real([](EndoscopeSimulationOptions& o) { o.calibrationDistortionErrorRelative = 0.03; }));
  // Zero coefficients are no distortion, except for a fisheye: the
  // equidistant lens is not the pinhole.
  EXPECT_FALSE(
    real([](EndoscopeSimulationOptions& o) { o.intrinsics.distortion = Eigen::Vector4d::Zero(); }));
  EXPECT_TRUE(real(
    [](EndoscopeSimulationOptions& o)
    {
      o.intrinsics.lensModel = LensModel::Fisheye;
      o.intrinsics.distortion = Eigen::Vector4d::Zero();
    }));
}

TEST(SimulatedVideo, RefusesAFisheyeWithoutFourCoefficientsAndAWildDistortionError)
{
  EndoscopeSimulationOptions o;
  o.intrinsics.lensModel = LensModel::Fisheye;
  o.intrinsics.distortion = Eigen::Matrix<double, 5, 1>::Zero();
  EXPECT_EQ(validationMessage(o),
    "the fisheye lens model needs exactly 4 distortion coefficients (k1, k2, k3, k4), not 5");
  o.intrinsics.distortion = Eigen::Vector4d(0.03, -0.01, 0.002, -0.0005);
  EXPECT_EQ(validationMessage(o), "no error");
  o.intrinsics.distortion(2) = 20.0;
  EXPECT_EQ(
    validationMessage(o), "the lens distortion coefficients must be finite and within [-10, 10]");
  o = EndoscopeSimulationOptions();
  o.calibrationDistortionErrorRelative = -1.0;
  EXPECT_EQ(validationMessage(o),
    "the calibration's relative distortion error must lie in (-1, 1), not -1");
}

TEST(SimulatedVideo, RefusesANegativeLatencyAWildFocalErrorAndAnOddNumberOfCoefficients)
{
  EndoscopeSimulationOptions o;
  o.trackerLatencyS = -0.01;
  EXPECT_EQ(validationMessage(o), "the tracker latency must be a finite number >= 0 s, not -0.01");
  o = EndoscopeSimulationOptions();
  o.calibrationFocalErrorRelative = 0.7;
  EXPECT_EQ(validationMessage(o),
    "the calibration's relative focal error must lie in (-0.5, 0.5), not 0.7");
  o = EndoscopeSimulationOptions();
  o.intrinsics.distortion = Eigen::Vector3d(-0.3, 0.1, 0.0);
  EXPECT_EQ(validationMessage(o),
    "the radial-tangential lens model needs 4, 5, 8, 12 or 14 distortion coefficients (OpenCV's "
    "k1, k2, p1, p2[, k3[, k4, k5, k6[, s1, s2, s3, s4[, tx, ty]]]]), not 3");
  // OpenCV's thin-prism model is a camera, but not one the simulation renders.
  o.intrinsics.distortion = Eigen::VectorXd::Zero(12);
  EXPECT_EQ(validationMessage(o),
    "the lens distortion needs 4, 5 or 8 coefficients (OpenCV's k1, k2, p1, p2[, k3[, k4, k5, "
    "k6]]), not 12");
  o = EndoscopeSimulationOptions();
  o.fieldStop.vignettingStrength = 2.0;
  EXPECT_EQ(validationMessage(o), "the vignetting strength must lie in [0, 1], not 2");
  o = EndoscopeSimulationOptions();
  o.trackerClockOffsetS = std::nan("");
  EXPECT_EQ(validationMessage(o), "the tracker's clock offset must be finite");
}

TEST(SimulatedVideo, TremorMakesTheWorldRealButTheStepAndTurnOfThePathDoNot)
{
  auto real = [](auto change)
  {
    EndoscopeSimulationOptions o;
    change(o);
    return !o.isIdealWorld();
  };
  EXPECT_TRUE(real([](EndoscopeSimulationOptions& o) { o.trajectory.jitterMm = 0.2; }));
  EXPECT_TRUE(real([](EndoscopeSimulationOptions& o) { o.trajectory.jitterDeg = 0.5; }));
  EXPECT_FALSE(real([](EndoscopeSimulationOptions& o) { o.trajectory.stepMm = 1.5; }));
  EXPECT_FALSE(real([](EndoscopeSimulationOptions& o) { o.trajectory.turnDegPerMm = 1.0; }));
}

TEST(SimulatedVideo, RefusesANegativeOrNonFiniteJitterOrTurnOfThePath)
{
  EndoscopeSimulationOptions o;
  o.trajectory.jitterMm = -0.1;
  EXPECT_EQ(validationMessage(o),
    "endoscope trajectory: the position jitter must be a finite number >= 0 mm, not -0.1");
  o = EndoscopeSimulationOptions();
  o.trajectory.jitterDeg = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validationMessage(o),
    "endoscope trajectory: the view jitter must be a finite number >= 0 degrees, not inf");
  o = EndoscopeSimulationOptions();
  o.trajectory.turnDegPerMm = std::nan("");
  EXPECT_EQ(validationMessage(o),
    "endoscope trajectory: the turn of the path must be a finite number >= 0 degrees per mm, not "
    "nan");
}
