#include <vimlop/Pipeline/ContourWindowRefinement.h>

#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/VisibleModelContours.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include "ErrorMessage.h"
#include "TestMeshes.h"
#include "TubeCameras.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vimlop
{
namespace
{

/// A frame's contour pairs as a perfect detector gives them: each visible
/// model contour sample where the true camera sees it.
std::vector<ContourPair> truePairs(
  const RegistrationModel& model, const PinholeCamera& k, const CameraPose& truth)
{
  std::vector<ContourPair> pairs;
  for (const ModelContourPoint& p : visibleModelContours(model, k, truth))
  {
    pairs.push_back({ 0, p.point, p.normal, p.pixel, p.pixelNormal });
  }
  return pairs;
}

/// Options that correct every window, whatever its contour error.
ContourWindowRefinementOptions correctingEveryWindow()
{
  ContourWindowRefinementOptions options;
  options.minErrorPx = 0.0;
  return options;
}

/// The rigid move of the world by `turnDeg` about `axis` through `centre`, then by `shiftMm`.
CameraPose moved(const CameraPose& pose, const Eigen::Vector3d& centre, double turnDeg,
  const Eigen::Vector3d& axis, const Eigen::Vector3d& shiftMm)
{
  const Eigen::Matrix3d r = Eigen::AngleAxisd(turnDeg * M_PI / 180.0, axis.normalized()).matrix();
  CameraPose out;
  out.rotation = r * pose.rotation;
  out.centre = centre + r * (pose.centre - centre) + shiftMm;
  return out;
}

TEST(ContourWindowRefinement, BringsADriftedTrackerBackOntoTheModelsContours)
{
  // A tracker whose poses drifted by a rigid move of the world (0.4 mm and
  // 0.8 degrees, the size of the drift measured on tracking's seed 3), and
  // that takes each correction (its next poses carry the drift left): the
  // contours alone bring it back to the true poses within a few frames.
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeTube(4.0, 60.0, 0.35));
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  const std::vector<CameraPose> truth = fixtures::camerasAlongTheTube(8);
  // The drift, as what it does to a true pose.
  Eigen::Matrix3d driftTurn =
    Eigen::AngleAxisd(0.8 * M_PI / 180.0, Eigen::Vector3d(1, 2, 0).normalized()).matrix();
  Eigen::Vector3d driftShift =
    Eigen::Vector3d(0.3, -0.2, 0.15) + truth[0].centre - driftTurn * truth[0].centre;
  ContourWindowRefinement refinement(correctingEveryWindow());
  double errorMm = 0.0;
  double errorDeg = 0.0;
  int corrections = 0;
  for (const CameraPose& t : truth)
  {
    CameraPose tracked;
    tracked.rotation = driftTurn * t.rotation;
    tracked.centre = driftTurn * t.centre + driftShift;
    const std::optional<CameraPose> corrected = refinement.add(k, tracked, truePairs(model, k, t));
    const CameraPose now = corrected ? *corrected : tracked;
    errorMm = (now.centre - t.centre).norm();
    errorDeg = rotationAngleBetween(now.rotation, t.rotation) * 180.0 / M_PI;
    if (corrected)
    {
      // The tracker moved with the correction: so does the drift.
      ++corrections;
      const Eigen::Matrix3d turn = corrected->rotation * tracked.rotation.transpose();
      driftShift = corrected->centre + turn * (driftShift - tracked.centre);
      driftTurn = turn * driftTurn;
    }
  }
  EXPECT_GE(corrections, 1);
  EXPECT_LT(errorMm, 0.02);
  EXPECT_LT(errorDeg, 0.05);
}

TEST(ContourWindowRefinement, LeavesAPoseAloneThatTheContoursAlreadyFit)
{
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeTube(4.0, 60.0, 0.35));
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  ContourWindowRefinement refinement(correctingEveryWindow());
  for (const CameraPose& t : fixtures::camerasAlongTheTube(3))
  {
    const std::optional<CameraPose> corrected = refinement.add(k, t, truePairs(model, k, t));
    if (corrected)
    {
      EXPECT_LT((corrected->centre - t.centre).norm(), 1e-6);
    }
  }
}

TEST(ContourWindowRefinement, LeavesAWindowAloneWhoseContoursLieWithinTheLeastErrorToCorrect)
{
  // 0.05 mm off: its contours lie a fraction of a pixel from the model's,
  // less than a detector's own error; with minErrorPx 1.5 it is left alone,
  // with 0 it is corrected.
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeTube(4.0, 60.0, 0.35));
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  const CameraPose t = fixtures::camerasAlongTheTube(1)[0];
  const CameraPose near =
    moved(t, t.centre, 0.0, Eigen::Vector3d::UnitX(), Eigen::Vector3d(0.05, 0.0, 0.0));
  EXPECT_EQ(ContourWindowRefinementOptions().minErrorPx, 1.5);
  EXPECT_FALSE(ContourWindowRefinement().add(k, near, truePairs(model, k, t)).has_value());
  // Nor is a window 0.6 mm off whose contours lie within the registration's
  // own contour error (a model that is not the anatomy).
  const CameraPose far =
    moved(t, t.centre, 0.0, Eigen::Vector3d::UnitX(), Eigen::Vector3d(0.0, 0.6, 0.0));
  ContourWindowRefinementOptions swollen;
  swollen.registeredErrorPx = 13.0;
  EXPECT_FALSE(ContourWindowRefinement(swollen).add(k, far, truePairs(model, k, t)).has_value());
  EXPECT_TRUE(ContourWindowRefinement().add(k, far, truePairs(model, k, t)).has_value());
  const std::optional<CameraPose> corrected =
    ContourWindowRefinement(correctingEveryWindow()).add(k, near, truePairs(model, k, t));
  ASSERT_TRUE(corrected.has_value());
  EXPECT_LT((corrected->centre - t.centre).norm(), 0.01);
}

TEST(ContourWindowRefinement, RefusesACorrectionAboveItsBoundsOrWithTooFewPairs)
{
  // 0.6 mm off with a bound of 0.3 mm: more likely wrong matches than a
  // drift, so nothing is applied; within a bound of 1 mm, it is.
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeTube(4.0, 60.0, 0.35));
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  const CameraPose t = fixtures::camerasAlongTheTube(1)[0];
  const CameraPose far =
    moved(t, t.centre, 0.0, Eigen::Vector3d::UnitX(), Eigen::Vector3d(0.0, 0.6, 0.0));
  ContourWindowRefinementOptions bounded = correctingEveryWindow();
  bounded.maxCorrectionMm = 0.3;
  EXPECT_FALSE(ContourWindowRefinement(bounded).add(k, far, truePairs(model, k, t)).has_value());
  bounded.maxCorrectionMm = 1.0;
  const std::optional<CameraPose> corrected =
    ContourWindowRefinement(bounded).add(k, far, truePairs(model, k, t));
  ASSERT_TRUE(corrected.has_value());
  EXPECT_LT((corrected->centre - t.centre).norm(), 0.02);
  std::vector<ContourPair> few = truePairs(model, k, t);
  few.resize(10);
  EXPECT_FALSE(ContourWindowRefinement(bounded).add(k, far, few).has_value());
  ContourWindowRefinementOptions bad;
  bad.windowFrames = 0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { ContourWindowRefinement{ bad }; }),
    "contour refinement: the window needs at least 1 frame, not 0");
  bad = {};
  bad.anchorTipDistanceMm = 0.0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { ContourWindowRefinement{ bad }; }),
    "contour refinement: the anchoring distance from the tracker's tip must be positive (mm), "
    "not 0");
  bad = {};
  bad.anchorTrackerTurnDeg = 0.0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { ContourWindowRefinement{ bad }; }),
    "contour refinement: the anchoring turn from the tracker's rotation must be positive "
    "(degrees), not 0");
}

} // namespace
} // namespace vimlop
