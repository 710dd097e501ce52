#include "TestFolders.h"
#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/EndoscopeSimulation.h>
#include <vimlop/Evaluation/FieldStop.h>
#include <vimlop/Rendering/MucosaTexture.h>
#include <vimlop/Rendering/vtkVIMLOPVirtualEndoscope.h>
#include <vimlop/Video/IntrinsicsIO.h>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <vtkNew.h>

#include <cmath>
#include <filesystem>
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

namespace
{

/// Mean absolute difference of two frames over a square of half-width `halfPx` around (u, v).
double meanDifference(const cv::Mat& a, const cv::Mat& b, int u, int v, int halfPx)
{
  const cv::Rect square(u - halfPx, v - halfPx, 2 * halfPx + 1, 2 * halfPx + 1);
  cv::Mat difference;
  cv::absdiff(a(square), b(square), difference);
  const cv::Scalar mean = cv::mean(difference);
  return (mean[0] + mean[1] + mean[2]) / 3.0;
}

} // namespace

TEST(EndoscopeSimulation, WithEveryErrorSourceOffTheFramesAreTheRenderersOwn)
{
  // The ideal world as it was before the error sources: the virtual
  // endoscope's frames, noise included, unchanged.
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeSimulationOptions o;
  o.frames = 2;
  ASSERT_TRUE(o.isIdealWorld());
  const SimulatedVideo video = simulateEndoscopeVideo(model, o, EvaluationProgress());
  MucosaTextureOptions texture;
  texture.seed = o.seed;
  vtkNew<vtkVIMLOPVirtualEndoscope> endoscope;
  endoscope->SetBlurSigmaPx(o.blurSigmaPx);
  endoscope->SetNoiseSigma(o.noiseSigma);
  endoscope->SetMesh(model.mesh(), MucosaTexture(texture));
  for (int f = 0; f < 2; ++f)
  {
    const EndoscopeImage image =
      endoscope->Render(o.intrinsics, video.camerasCT[f], o.seed * 100003ull + f);
    int differing = 0;
    for (int v = 0; v < image.heightPx; ++v)
    {
      for (int u = 0; u < image.widthPx; ++u)
      {
        const cv::Vec3b bgr = video.frames[f].at<cv::Vec3b>(v, u);
        differing +=
          bgr != cv::Vec3b(image.channel(u, v, 2), image.channel(u, v, 1), image.channel(u, v, 0));
      }
    }
    EXPECT_EQ(differing, 0) << "frame " << f;
    EXPECT_EQ(video.depth[f].depthMm, image.depth.depthMm);
  }
  EXPECT_EQ(video.calibratedIntrinsics.fx, video.intrinsics.fx);
  EXPECT_EQ(video.calibratedIntrinsics.distortion.size(), 0);
}

TEST(EndoscopeSimulation, TheFieldStopBlackensTheBorderLeavesTheCentreAndKeepsTheSensorNoise)
{
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeSimulationOptions o;
  o.frames = 2;
  o.noiseSigma = 0.0;
  const SimulatedVideo open = simulateEndoscopeVideo(model, o, EvaluationProgress());
  o.fieldStop.radiusFraction = 0.6; // 120 px
  const SimulatedVideo stopped = simulateEndoscopeVideo(model, o, EvaluationProgress());
  const cv::Mat gain = fieldStopGain(o.fieldStop, 320, 240);
  int inside = 0;
  int outside = 0;
  for (int v = 0; v < 240; ++v)
  {
    for (int u = 0; u < 320; ++u)
    {
      const cv::Vec3b seen = stopped.frames[1].at<cv::Vec3b>(v, u);
      if (gain.at<float>(v, u) == 1.0f)
      {
        ++inside;
        ASSERT_EQ(seen, open.frames[1].at<cv::Vec3b>(v, u)) << u << ", " << v;
      }
      else if (gain.at<float>(v, u) == 0.0f)
      {
        ++outside;
        ASSERT_EQ(seen, cv::Vec3b(0, 0, 0)) << u << ", " << v;
      }
    }
  }
  EXPECT_GT(inside, 40000);  // about pi 119^2
  EXPECT_GT(outside, 25000); // about 320 x 240 - pi 121^2
  EXPECT_GT(cv::countNonZero(open.frames[1].reshape(1) != 0), 0.9 * 320 * 240 * 3);

  // With vignetting the edge of the circle is darker than its centre by the set amount.
  o.fieldStop.vignettingStrength = 0.5;
  const SimulatedVideo vignetted = simulateEndoscopeVideo(model, o, EvaluationProgress());
  const cv::Mat& a = open.frames[1];
  const cv::Mat& b = vignetted.frames[1];
  EXPECT_LE(meanDifference(a, b, 160, 120, 2), 0.5);
  // 110 px out (r / R = 0.917): the gain is 1 - 0.5 * 0.84 = 0.58.
  const cv::Vec3b edgeOpen = a.at<cv::Vec3b>(120, 270);
  const cv::Vec3b edgeDark = b.at<cv::Vec3b>(120, 270);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(edgeDark[c], 0.58 * edgeOpen[c], 1.0) << c;
  }

  // A real sensor is noisy in the black border too.
  o.noiseSigma = 3.0;
  o.fieldStop.vignettingStrength = 0.0;
  const SimulatedVideo noisy = simulateEndoscopeVideo(model, o, EvaluationProgress());
  EXPECT_GT(cv::countNonZero(noisy.frames[1](cv::Rect(0, 0, 20, 20)).reshape(1)), 100);
}

TEST(EndoscopeSimulation, LensDistortionKeepsTheCentreAndMovesTheRestOfTheFrame)
{
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeSimulationOptions o;
  o.frames = 2;
  o.noiseSigma = 0.0;
  const SimulatedVideo pinhole = simulateEndoscopeVideo(model, o, EvaluationProgress());
  o.intrinsics.distortion = Eigen::Vector4d(-0.3, 0.0, 0.0, 0.0);
  const SimulatedVideo distorted = simulateEndoscopeVideo(model, o, EvaluationProgress());
  ASSERT_EQ(distorted.camerasCT[1].centre, pinhole.camerasCT[1].centre);
  // The optical axis sees the same through both lenses (the renderer draws the
  // wider pinhole view on the same pixel grid) ...
  EXPECT_LE(meanDifference(pinhole.frames[1], distorted.frames[1], 160, 120, 1), 2.0);
  EXPECT_NEAR(distorted.depth[1].at(160, 120), pinhole.depth[1].at(160, 120),
    1e-3 * pinhole.depth[1].at(160, 120));
  // ... and farther out the barrel lens shows what lies farther out.
  EXPECT_GT(meanDifference(pinhole.frames[1], distorted.frames[1], 40, 40, 10), 5.0);
  EXPECT_EQ(distorted.calibratedIntrinsics.distortion, o.intrinsics.distortion);
}

TEST(EndoscopeSimulation, AFisheyeLensKeepsTheCentreAndShowsMoreOfTheAirwayFartherOut)
{
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeSimulationOptions o;
  o.frames = 2;
  o.noiseSigma = 0.0;
  const SimulatedVideo pinhole = simulateEndoscopeVideo(model, o, EvaluationProgress());
  o.intrinsics.lensModel = LensModel::Fisheye;
  o.intrinsics.distortion = Eigen::Vector4d(0.03, -0.01, 0.002, -0.0005);
  const SimulatedVideo fisheye = simulateEndoscopeVideo(model, o, EvaluationProgress());
  ASSERT_EQ(fisheye.camerasCT[1].centre, pinhole.camerasCT[1].centre);
  EXPECT_LE(meanDifference(pinhole.frames[1], fisheye.frames[1], 160, 120, 1), 2.0);
  EXPECT_NEAR(fisheye.depth[1].at(160, 120), pinhole.depth[1].at(160, 120),
    1e-3 * pinhole.depth[1].at(160, 120));
  EXPECT_GT(meanDifference(pinhole.frames[1], fisheye.frames[1], 40, 40, 10), 5.0);
  EXPECT_EQ(fisheye.calibratedIntrinsics.lensModel, LensModel::Fisheye);
  EXPECT_EQ(fisheye.calibratedIntrinsics.distortion, o.intrinsics.distortion);
}

TEST(EndoscopeSimulation, TheGivenDistortionCoefficientsAreOffByTheCalibrationsDistortionError)
{
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeSimulationOptions o;
  o.frames = 2;
  o.intrinsics.distortion = Eigen::Vector4d(-0.35, 0.1, 0.001, -0.002);
  const SimulatedVideo exact = simulateEndoscopeVideo(model, o, EvaluationProgress());
  o.calibrationDistortionErrorRelative = 0.04;
  const SimulatedVideo video = simulateEndoscopeVideo(model, o, EvaluationProgress());
  // The frames are the true lens's, whatever the calibration says.
  EXPECT_EQ(cv::countNonZero(exact.frames[1].reshape(1) != video.frames[1].reshape(1)), 0);
  const std::filesystem::path folder = fixtures::freshTestFolder("simulated-distortion-error");
  writeSimulatedVideo(video, folder.string());
  const PinholeCamera given = readIntrinsics((folder / "intrinsics.yaml").string());
  const PinholeCamera truth = readIntrinsics((folder / "truth" / "intrinsics.yaml").string());
  EXPECT_EQ(truth.distortion, o.intrinsics.distortion);
  ASSERT_EQ(given.distortion.size(), 4);
  for (Eigen::Index i = 0; i < 4; ++i)
  {
    EXPECT_NEAR(given.distortion[i] / truth.distortion[i] - 1.0, 0.04, 1e-12) << i;
  }
  EXPECT_EQ(given.fx, truth.fx);

  // A fisheye's four coefficients alike, and the given file says it is one.
  o.intrinsics.lensModel = LensModel::Fisheye;
  o.intrinsics.distortion = Eigen::Vector4d(0.03, -0.01, 0.002, -0.0005);
  o.calibrationDistortionErrorRelative = -0.05;
  o.frames = 2;
  const SimulatedVideo fisheye = simulateEndoscopeVideo(model, o, EvaluationProgress());
  writeSimulatedVideo(fisheye, folder.string());
  const PinholeCamera givenFisheye = readIntrinsics((folder / "intrinsics.yaml").string());
  EXPECT_EQ(givenFisheye.lensModel, LensModel::Fisheye);
  for (Eigen::Index i = 0; i < 4; ++i)
  {
    EXPECT_NEAR(givenFisheye.distortion[i] / o.intrinsics.distortion[i] - 1.0, -0.05, 1e-12) << i;
  }
}

TEST(EndoscopeSimulation, WritesWhatAUserHasAndTheTrueIntrinsicsPosesAndDepthApart)
{
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeSimulationOptions o;
  o.frames = 2;
  o.intrinsics.distortion = Eigen::Vector4d(-0.1, 0.01, 0.0, 0.0);
  const SimulatedVideo exact = simulateEndoscopeVideo(model, o, EvaluationProgress());
  o.calibrationFocalErrorRelative = 0.02;
  o.calibrationPrincipalPointErrorPx = Eigen::Vector2d(3.0, -2.0);
  const SimulatedVideo video = simulateEndoscopeVideo(model, o, EvaluationProgress());
  // The frames are the true camera's, whatever the calibration says.
  EXPECT_EQ(cv::countNonZero(exact.frames[1].reshape(1) != video.frames[1].reshape(1)), 0);

  const std::filesystem::path folder =
    std::filesystem::path(::testing::TempDir()) / "simulated-calibration";
  std::filesystem::remove_all(folder);
  writeSimulatedVideo(video, folder.string());
  const PinholeCamera given = readIntrinsics((folder / "intrinsics.yaml").string());
  const PinholeCamera truth = readIntrinsics((folder / "truth" / "intrinsics.yaml").string());
  EXPECT_DOUBLE_EQ(given.fx, 1.02 * 200.0);
  EXPECT_DOUBLE_EQ(given.fy, 1.02 * 200.0);
  EXPECT_DOUBLE_EQ(given.cx, 159.5 + 3.0);
  EXPECT_DOUBLE_EQ(given.cy, 119.5 - 2.0);
  EXPECT_EQ(given.distortion, o.intrinsics.distortion);
  EXPECT_DOUBLE_EQ(truth.fx, 200.0);
  EXPECT_DOUBLE_EQ(truth.fy, 200.0);
  EXPECT_DOUBLE_EQ(truth.cx, 159.5);
  EXPECT_DOUBLE_EQ(truth.cy, 119.5);
  EXPECT_EQ(truth.distortion, o.intrinsics.distortion);
  // What a user has beside the frames; the truth apart, under truth/.
  namespace fs = std::filesystem;
  EXPECT_TRUE(fs::exists(folder / "frames" / "frame000.png"));
  EXPECT_TRUE(fs::exists(folder / "tracker.csv"));
  EXPECT_TRUE(fs::exists(folder / "truth" / "poses.json"));
  EXPECT_TRUE(fs::exists(folder / "truth" / "depth" / "frame000.tiff"));
  EXPECT_FALSE(fs::exists(folder / "poses.json"));
  EXPECT_FALSE(fs::exists(folder / "depth"));
}

TEST(EndoscopeSimulation, WithEveryVideoArtifactOffTheFramesAreByteIdentical)
{
  // The artifacts' secondary settings (samples, angle, area, opacity,
  // quality) change nothing while their main knobs are off, on the
  // renderer's path and on the optics' path (a field stop) alike.
  const RegistrationModel model(fixtures::makeTube());
  for (const double circle : { 0.0, 0.6 })
  {
    EndoscopeSimulationOptions plain;
    plain.frames = 2;
    plain.fieldStop.radiusFraction = circle;
    EndoscopeSimulationOptions off = plain;
    off.artifacts.motionBlurSamples = 3;
    off.artifacts.specularAngleDeg = 20.0;
    off.artifacts.occluderAreaFraction = 0.5;
    off.artifacts.occluderOpacity = 0.3;
    ASSERT_TRUE(off.artifacts.isOff());
    EXPECT_EQ(off.isIdealWorld(), circle == 0.0);
    const SimulatedVideo a = simulateEndoscopeVideo(model, plain, EvaluationProgress());
    const SimulatedVideo b = simulateEndoscopeVideo(model, off, EvaluationProgress());
    ASSERT_EQ(a.frames.size(), b.frames.size());
    for (size_t f = 0; f < a.frames.size(); ++f)
    {
      EXPECT_EQ(cv::norm(a.frames[f], b.frames[f], cv::NORM_INF), 0.0)
        << "circle " << circle << ", frame " << f;
    }
  }
}

TEST(EndoscopeSimulation, TheVideoArtifactsChangeTheFramesButNotTheirCountOrDepth)
{
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeSimulationOptions o;
  o.frames = 4;
  const SimulatedVideo ideal = simulateEndoscopeVideo(model, o, EvaluationProgress());
  VideoArtifactOptions& a = o.artifacts;
  a.exposureTimeS = 1.0 / 30.0;
  a.specularStrength = 1.5;
  a.exposureGain = 1.3;
  a.shotNoise = 0.3;
  a.occludedFrameFraction = 0.5;
  a.occluderAreaFraction = 0.2;
  a.compression = VideoCompression::Mjpg;
  a.compressionQuality = 80;
  EXPECT_FALSE(o.isIdealWorld());
  const SimulatedVideo real = simulateEndoscopeVideo(model, o, EvaluationProgress());
  ASSERT_EQ(real.frames.size(), 4u);
  for (size_t f = 0; f < 4; ++f)
  {
    ASSERT_EQ(real.frames[f].size(), ideal.frames[f].size());
    EXPECT_GT(cv::norm(real.frames[f], ideal.frames[f], cv::NORM_L1) / (320.0 * 240 * 3), 2.0)
      << "frame " << f;
    EXPECT_EQ(real.depth[f].depthMm, ideal.depth[f].depthMm) << "frame " << f;
  }
  // The same seed, the same sequence.
  const SimulatedVideo again = simulateEndoscopeVideo(model, o, EvaluationProgress());
  EXPECT_EQ(cv::norm(again.frames[2], real.frames[2], cv::NORM_INF), 0.0);
}

TEST(EndoscopeSimulation, TheTremorAndTheTurnOfThePathReachTheRenderedSequence)
{
  const RegistrationModel model(fixtures::makeTube(6.0, 80.0));
  EndoscopeSimulationOptions o;
  o.frames = 4;
  const SimulatedVideo smooth = simulateEndoscopeVideo(model, o, EvaluationProgress());
  o.trajectory.jitterMm = 0.3;
  o.trajectory.jitterDeg = 0.5;
  const SimulatedVideo shaken = simulateEndoscopeVideo(model, o, EvaluationProgress());
  ASSERT_EQ(shaken.camerasCT.size(), 4u);
  double offsetMm = 0.0;
  for (size_t f = 0; f < shaken.camerasCT.size(); ++f)
  {
    offsetMm = std::max(offsetMm, (shaken.camerasCT[f].centre - smooth.camerasCT[f].centre).norm());
  }
  EXPECT_GT(offsetMm, 0.05);
  EXPECT_LT(offsetMm, 2.0);
  EXPECT_GT(cv::norm(shaken.frames[1], smooth.frames[1], cv::NORM_L1), 0.0);
  // A bad value is refused before anything is rendered.
  o.trajectory.turnDegPerMm = -1.0;
  try
  {
    simulateEndoscopeVideo(model, o, EvaluationProgress());
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(),
      "endoscope trajectory: the turn of the path must be a finite number >= 0 degrees per mm, "
      "not -1");
  }
}
