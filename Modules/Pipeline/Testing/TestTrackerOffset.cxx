#include <vimlop/Pipeline/TrackerOffset.h>

#include "ErrorMessage.h"
#include <vimlop/Core/Rotation.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

namespace vimlop
{
namespace
{

/// A camera at frame `f` of a scope moving along x and turning about y.
CameraPose cameraAt(int f)
{
  CameraPose pose;
  pose.centre = Eigen::Vector3d(0.5 * f, 2.0, -1.0);
  pose.rotation = Eigen::AngleAxisd(0.02 * f, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return pose;
}

TEST(TrackerOffset, LearnsATrackersShiftAndTurnThroughItsNoiseAndTakesThemOff)
{
  // A 6-DOF tracker 1 mm and 1.5 degrees off, with 0.2 mm and 0.3 degrees of
  // noise per axis, against a video that sees the camera exactly: after 90
  // frames the error left on a new reading is its noise's share, far below
  // the error itself.
  const Eigen::Vector3d shiftMm(0.8, 0.0, -0.6);
  const Eigen::Matrix3d turn =
    Eigen::AngleAxisd(1.5 * M_PI / 180.0, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  std::mt19937 rng(7);
  std::normal_distribution<double> mm(0.0, 0.2);
  std::normal_distribution<double> rad(0.0, 0.3 * M_PI / 180.0);
  const auto reading = [&](const CameraPose& truth)
  {
    return TrackerPrior(truth.centre - shiftMm + Eigen::Vector3d(mm(rng), mm(rng), mm(rng)),
      rotationFromVector(Eigen::Vector3d(rad(rng), rad(rng), rad(rng))) * turn.transpose() *
        truth.rotation);
  };
  TrackerOffset offset(90);
  EXPECT_EQ(offset.framesLearned(), 0);
  for (int f = 0; f < 90; ++f)
  {
    const CameraPose truth = cameraAt(f);
    offset.learn(truth, reading(truth));
  }
  EXPECT_EQ(offset.framesLearned(), 90);
  EXPECT_LT((offset.shiftMm() - shiftMm).norm(), 0.1);
  EXPECT_NEAR(offset.turnDeg(), 1.5, 0.15);
  const CameraPose truth = cameraAt(100);
  const TrackerPrior raw(truth.centre - shiftMm, turn.transpose() * truth.rotation);
  const TrackerPrior corrected = offset.corrected(raw);
  EXPECT_LT((corrected.tipCT - truth.centre).norm(), 0.1);
  EXPECT_LT(rotationAngleBetween(*corrected.rotationCT, truth.rotation) * 180.0 / M_PI, 0.15);
  EXPECT_TRUE(isRotation(*corrected.rotationCT));

  // A position-only reading is shifted and stays without a rotation.
  EXPECT_FALSE(offset.corrected(TrackerPrior(truth.centre)).rotationCT);
  offset.clear();
  EXPECT_EQ(offset.framesLearned(), 0);
  EXPECT_EQ(offset.corrected(raw).tipCT, raw.tipCT);
}

TEST(TrackerOffset, TakesOffOnlyAShareOfWhatAFewFramesSawUntilItIsChecked)
{
  // Shrunk as if 30 frames had seen no error: 3 frames of a 2 mm shift take
  // off 3/33 of it, 30 frames half of it, 300 frames 10/11; the position is
  // checked once 30 frames have measured it, the rotation of a tracker
  // without one never.
  TrackerOffset offset(1000, 30);
  const Eigen::Vector3d shiftMm(0.0, 2.0, 0.0);
  int f = 0;
  const auto learnUpTo = [&](int frames)
  {
    for (; f < frames; ++f)
    {
      const CameraPose truth = cameraAt(f);
      offset.learn(truth, TrackerPrior(truth.centre - shiftMm));
    }
  };
  learnUpTo(3);
  EXPECT_NEAR(offset.shiftMm().y(), 2.0 * 3.0 / 33.0, 1e-12);
  EXPECT_FALSE(offset.positionChecked());
  learnUpTo(30);
  EXPECT_NEAR(offset.shiftMm().y(), 1.0, 1e-12);
  EXPECT_TRUE(offset.positionChecked());
  EXPECT_FALSE(offset.rotationChecked());
  learnUpTo(300);
  EXPECT_NEAR(offset.shiftMm().y(), 2.0 * 300.0 / 330.0, 1e-12);
  EXPECT_EQ(fixtures::errorMessageOf([] { TrackerOffset(10, -1); }),
    "tracker offset: its prior frames must not be negative, not -1");
}

TEST(TrackerOffset, FollowsAnErrorThatChangesOverItsMemory)
{
  // The error jumps from 1 mm one way to 1 mm the other: with a memory of
  // 10 frames, 60 frames later only exp(-6) of the old error is left.
  TrackerOffset offset(10);
  for (int f = 0; f < 100; ++f)
  {
    const CameraPose truth = cameraAt(f);
    const Eigen::Vector3d shiftMm(f < 40 ? 1.0 : -1.0, 0.0, 0.0);
    offset.learn(truth, TrackerPrior(truth.centre - shiftMm));
  }
  EXPECT_NEAR(offset.shiftMm().x(), -1.0, 0.01);
  EXPECT_EQ(offset.turnDeg(), 0.0);
  EXPECT_EQ(fixtures::errorMessageOf([] { TrackerOffset(0); }),
    "tracker offset: its memory must be at least 1 frame, not 0");
}

} // namespace
} // namespace vimlop
