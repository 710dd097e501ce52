#include "ErrorMessage.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/WorldPreset.h>

#include <gtest/gtest.h>

#include <set>

using namespace vimlop;

namespace
{

bool isIdeal(const WorldSettings& w)
{
  return w.model.isIdealWorld() && w.video.isIdealWorld();
}

} // namespace

TEST(WorldPreset, ClinicalTurnsOnEverySourceAndIdealTurnsThemAllOffAgain)
{
  WorldSettings w;
  w.video.frames = 12; // not an error source: kept
  applyWorldPreset(w, "clinical");
  EXPECT_EQ(w.video.frames, 12);
  EXPECT_EQ(w.model.anatomyDeformationMm, 5.0);
  EXPECT_EQ(w.model.segmentationOffsetHU, -100.0);
  EXPECT_EQ(w.model.truthTriangles, 0);
  EXPECT_EQ(w.model.swelling.swellingMm, 1.5);
  EXPECT_EQ(w.video.fieldStop.radiusFraction, 0.6);
  EXPECT_EQ(w.video.fieldStop.vignettingStrength, 0.4);
  ASSERT_EQ(w.video.intrinsics.distortion.size(), 4);
  EXPECT_DOUBLE_EQ(w.video.intrinsics.distortion(1), 0.1);
  EXPECT_EQ(w.video.calibrationFocalErrorRelative, 0.01);
  EXPECT_EQ(w.video.trackerLatencyS, 0.03);
  EXPECT_DOUBLE_EQ(w.video.trackerClockOffsetS, 0.05);
  EXPECT_EQ(w.video.trajectory.uprightRollDeg, 45.0);
  EXPECT_EQ(w.video.artifacts.exposureTimeS, 1.0 / 60.0);
  EXPECT_EQ(w.video.artifacts.compression, VideoCompression::Mjpg);
  EXPECT_EQ(w.video.artifacts.compressionQuality, 75);
  EXPECT_EQ(w.video.artifacts.occludedFrameFraction, 0.1);
  EXPECT_NO_THROW(w.model.validate());
  EXPECT_NO_THROW(w.video.validate());

  applyWorldPreset(w, "ideal");
  EXPECT_TRUE(isIdeal(w));
  EXPECT_EQ(w.video.trajectory.uprightRollDeg, 10.0);
  EXPECT_EQ(w.video.frames, 12);
}

TEST(WorldPreset, EachSourceAloneLeavesTheIdealWorldAndComesBackToIt)
{
  std::set<std::string> names;
  for (const ErrorSource& source : errorSources())
  {
    EXPECT_TRUE(names.insert(source.name).second) << source.name << " twice";
    WorldSettings w;
    applyWorldPreset(w, "ideal");
    source.set(w, source.clinicalValue);
    // Roll, the step and the turn are path settings, not errors of the
    // world's model or video.
    if (source.name != "roll" && source.name != "fast-motion" && source.name != "curved-path")
    {
      EXPECT_FALSE(isIdeal(w)) << source.name;
    }
    for (const ErrorSource& other : errorSources())
    {
      // "distortion-calibration" switches on the "lens" source's lens and,
      // when off, removes it: the one pair of sources that share a knob.
      const bool shareTheLens = source.name == "lens" && other.name == "distortion-calibration";
      if (other.name != source.name && !shareTheLens)
      {
        // Only its own knobs: the others' are still off.
        WorldSettings alone = w;
        other.set(alone, other.offValue);
        EXPECT_EQ(isIdeal(alone), isIdeal(w)) << source.name << " and " << other.name;
      }
    }
    source.set(w, source.offValue);
    EXPECT_TRUE(isIdeal(w)) << source.name;
    EXPECT_EQ(&errorSource(source.name), &source);
  }
  EXPECT_EQ(fixtures::errorMessageOf([] { errorSource("weather"); }),
    "unknown error source 'weather' (expected one of anatomy, segmentation, swelling, "
    "image-circle, lens, calibration, tracker, roll, motion-blur, specular, exposure, shot-noise, "
    "compression, occluders, fisheye, distortion-calibration, fast-motion, jitter, curved-path)");
  WorldSettings w;
  EXPECT_EQ(fixtures::errorMessageOf([&] { applyWorldPreset(w, "mars"); }),
    "unknown world 'mars' (expected ideal or clinical)");
}

TEST(WorldPreset, TheClinicalPresetLeavesTheBudgetOnlySourcesOff)
{
  // The README's clinical figures were measured without the fisheye and the
  // distortion's calibration error: the clinical world stays that world.
  WorldSettings w;
  applyWorldPreset(w, "clinical");
  EXPECT_EQ(w.video.intrinsics.lensModel, LensModel::RadialTangential);
  ASSERT_EQ(w.video.intrinsics.distortion.size(), 4);
  EXPECT_EQ(w.video.intrinsics.distortion(0), -0.35);
  EXPECT_DOUBLE_EQ(w.video.intrinsics.distortion(1), 0.1);
  EXPECT_EQ(w.video.calibrationDistortionErrorRelative, 0.0);
  for (const char* name : { "fisheye", "distortion-calibration" })
  {
    EXPECT_FALSE(errorSource(name).inClinicalPreset) << name;
  }
  for (const char* name : { "anatomy", "lens", "calibration", "occluders" })
  {
    EXPECT_TRUE(errorSource(name).inClinicalPreset) << name;
  }
  // The ideal world has no lens of either model.
  WorldSettings fisheye;
  errorSource("fisheye").set(fisheye, 1.0);
  ASSERT_EQ(fisheye.video.intrinsics.lensModel, LensModel::Fisheye);
  applyWorldPreset(fisheye, "ideal");
  EXPECT_TRUE(isIdeal(fisheye));
}

TEST(WorldPreset, TheFisheyeAndTheDistortionsCalibrationErrorEachSwitchOnALens)
{
  WorldSettings w;
  const ErrorSource& fisheye = errorSource("fisheye");
  fisheye.set(w, 0.25);
  EXPECT_EQ(w.video.intrinsics.lensModel, LensModel::Fisheye);
  // s = 0.25: three quarters of tan's Taylor coefficients.
  EXPECT_DOUBLE_EQ(w.video.intrinsics.distortion(0), 0.75 / 3.0);
  EXPECT_DOUBLE_EQ(w.video.intrinsics.distortion(3), 0.75 * 62.0 / 2835.0);
  EXPECT_NO_THROW(w.video.validate());
  fisheye.set(w, fisheye.clinicalValue);
  EXPECT_EQ(w.video.intrinsics.distortion, Eigen::Vector4d::Zero());
  EXPECT_FALSE(isIdeal(w));
  // The calibration error acts on the lens there is (here the fisheye).
  const ErrorSource& calibration = errorSource("distortion-calibration");
  calibration.set(w, calibration.clinicalValue);
  EXPECT_EQ(w.video.intrinsics.lensModel, LensModel::Fisheye);
  EXPECT_EQ(w.video.calibrationDistortionErrorRelative, 0.03);
  // Alone, it brings the "lens" source's lens.
  WorldSettings alone;
  calibration.set(alone, calibration.clinicalValue);
  EXPECT_EQ(alone.video.intrinsics.lensModel, LensModel::RadialTangential);
  EXPECT_EQ(alone.video.intrinsics.distortion, Eigen::Vector4d(-0.35, 0.1, 0.0, 0.0));
  EXPECT_NO_THROW(alone.video.validate());
  calibration.set(alone, 0.0);
  EXPECT_TRUE(isIdeal(alone));
}

TEST(WorldPreset, TheClinicalPresetLeavesTheMotionSourcesAsTheyWere)
{
  WorldSettings w;
  w.video.trajectory.jitterMm = 0.3; // given by its own flag: kept by the clinical preset
  applyWorldPreset(w, "clinical");
  EXPECT_EQ(w.video.trajectory.stepMm, 0.5);
  EXPECT_EQ(w.video.trajectory.jitterMm, 0.3);
  EXPECT_EQ(w.video.trajectory.jitterDeg, 0.0);
  EXPECT_EQ(w.video.trajectory.turnDegPerMm, 0.0);
  // The ideal world turns every source off, those outside the preset too.
  applyWorldPreset(w, "ideal");
  EXPECT_EQ(w.video.trajectory.jitterMm, 0.0);
  std::set<std::string> outside;
  for (const ErrorSource& source : errorSources())
  {
    if (!source.inClinicalPreset)
    {
      outside.insert(source.name);
    }
  }
  EXPECT_EQ(outside,
    (std::set<std::string>{
      "fisheye", "distortion-calibration", "fast-motion", "jitter", "curved-path" }));
}

TEST(WorldPreset, TheMotionSourcesSetThePathAtTheirRealisticValues)
{
  WorldSettings w;
  errorSource("fast-motion").set(w, errorSource("fast-motion").clinicalValue);
  errorSource("jitter").set(w, errorSource("jitter").clinicalValue);
  errorSource("curved-path").set(w, errorSource("curved-path").clinicalValue);
  EXPECT_EQ(w.video.trajectory.stepMm, 1.5);
  EXPECT_EQ(w.video.trajectory.jitterMm, 0.25);
  EXPECT_EQ(w.video.trajectory.jitterDeg, 0.5);
  EXPECT_EQ(w.video.trajectory.turnDegPerMm, 1.0);
  EXPECT_NO_THROW(w.video.validate());
  EXPECT_FALSE(w.video.isIdealWorld());
}
