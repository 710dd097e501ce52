#include "ErrorMessage.h"
#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Rendering/EndoscopeTrajectory.h>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace vimlop;

namespace
{

PinholeCamera endoscope()
{
  PinholeCamera k;
  k.fx = k.fy = 200.0;
  k.cx = 159.5;
  k.cy = 119.5;
  k.widthPx = 320;
  k.heightPx = 240;
  return k;
}

EndoscopeTrajectoryOptions tubeOptions()
{
  EndoscopeTrajectoryOptions o;
  o.intrinsics = endoscope();
  o.minContourSamples = 50;
  return o;
}

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

} // namespace

TEST(EndoscopeTrajectory, StaysInsideAndMovesAlongThePassage)
{
  const TriangleMesh tube = fixtures::makeTube();
  ASSERT_LT(tube.signedVolume(), 0.0); // normals into the air
  const RegistrationModel model(tube);
  const EndoscopeTrajectoryOptions o = tubeOptions();
  const std::vector<CameraPose> path = makeEndoscopeTrajectory(model, o, 3);
  ASSERT_EQ(path.size(), 30u);
  const Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  for (size_t f = 0; f < path.size(); ++f)
  {
    const Eigen::Vector3d& c = path[f].centre;
    EXPECT_TRUE(model.isInside(c)) << f;
    EXPECT_GE(model.locator().closestPoint(c).distanceMm, o.minClearanceMm - 1e-9) << f;
    // Looking along the passage (either way), within the wobble.
    const double view = angleDeg(path[f].viewDirection(), axis);
    EXPECT_LT(std::min(view, 180.0 - view), 20.0) << f;
    if (f > 0)
    {
      const Eigen::Vector3d step = c - path[f - 1].centre;
      // The advance is along the axis; the sway adds a little sideways.
      EXPECT_NEAR(std::abs(step.dot(axis)), o.stepMm, 0.02) << f;
      EXPECT_LT(step.norm(), o.stepMm + 0.25) << f;
      // Smooth: the view turns by about a degree per frame at most.
      EXPECT_LT(angleDeg(path[f].viewDirection(), path[f - 1].viewDirection()), 1.5) << f;
    }
    if (f > 1)
    {
      // The sway's acceleration is A w^2 (1 + 0.7 x 1.37^2) at most, w = 2 pi / period.
      const double w = 2.0 * M_PI / o.swayPeriodFrames;
      const Eigen::Vector3d acceleration = c - 2.0 * path[f - 1].centre + path[f - 2].centre;
      EXPECT_LT(acceleration.norm(), 1.01 * o.swayAmplitudeMm * w * w * (1.0 + 0.7 * 1.37 * 1.37))
        << f;
    }
  }
  // The path runs along the tube, not across it.
  const double travel = angleDeg(path.back().centre - path.front().centre, axis);
  EXPECT_LT(std::min(travel, 180.0 - travel), 5.0);
  // The scope moves the way it looks.
  EXPECT_GT((path.back().centre - path.front().centre).dot(path.front().viewDirection()), 0.0);
}

TEST(EndoscopeTrajectory, IsReproducibleFromTheSeed)
{
  const RegistrationModel model(fixtures::makeTube());
  const std::vector<CameraPose> a = makeEndoscopeTrajectory(model, tubeOptions(), 5);
  const std::vector<CameraPose> b = makeEndoscopeTrajectory(model, tubeOptions(), 5);
  const std::vector<CameraPose> c = makeEndoscopeTrajectory(model, tubeOptions(), 6);
  for (size_t f = 0; f < a.size(); ++f)
  {
    EXPECT_EQ(a[f].centre, b[f].centre);
    EXPECT_EQ(a[f].rotation, b[f].rotation);
  }
  EXPECT_GT((a.front().centre - c.front().centre).norm(), 1e-6);
}

TEST(EndoscopeTrajectory, FailsWhereTheScopeDoesNotFit)
{
  // A 3 mm wide tube cannot hold a scope 2 mm from every wall.
  const RegistrationModel model(fixtures::makeTube(1.5, 60.0, 0.0));
  EndoscopeTrajectoryOptions o = tubeOptions();
  o.maxAttempts = 300;
  try
  {
    makeEndoscopeTrajectory(model, o, 1);
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("found no straight passage of 22.5 mm with 2.0"),
      std::string::npos)
      << e.what();
  }
}

TEST(EndoscopeTrajectory, UprightScopeKeepsTheImageUpNearSuperior)
{
  // The tube runs along z (superior), so the upright scope's up is anterior (-y).
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeTrajectoryOptions o = tubeOptions();
  o.uprightRollDeg = 10.0;
  double largest = 0.0;
  for (std::uint64_t seed : { 1u, 2u, 3u, 4u })
  {
    for (const CameraPose& pose : makeEndoscopeTrajectory(model, o, seed))
    {
      const Eigen::Vector3d look = pose.viewDirection();
      Eigen::Vector3d anterior = -Eigen::Vector3d::UnitY();
      anterior -= anterior.dot(look) * look;
      largest = std::max(largest, angleDeg(-pose.rotation.col(1), anterior));
    }
  }
  // The roll offset, plus half the view wobble.
  EXPECT_LT(largest, o.uprightRollDeg + 0.5 * o.viewSwayDeg + 0.5);
  EXPECT_GT(largest, 1.0);
}

namespace
{

/// Root-mean-square distance between the optical centres of two paths, mm.
double rmsCentreDistanceMm(const std::vector<CameraPose>& a, const std::vector<CameraPose>& b)
{
  double sum = 0.0;
  for (size_t f = 0; f < a.size(); ++f)
  {
    sum += (a[f].centre - b[f].centre).squaredNorm();
  }
  return std::sqrt(sum / a.size());
}

/// Root-mean-square angle between the rotations of two paths, degrees.
double rmsRotationDeg(const std::vector<CameraPose>& a, const std::vector<CameraPose>& b)
{
  double sum = 0.0;
  for (size_t f = 0; f < a.size(); ++f)
  {
    const double angle =
      Eigen::AngleAxisd(a[f].rotation.transpose() * b[f].rotation).angle() * 180.0 / M_PI;
    sum += angle * angle;
  }
  return std::sqrt(sum / a.size());
}

} // namespace

TEST(EndoscopeTrajectory, WithoutJitterOrTurnThePathIsTheSmoothOneBitForBit)
{
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeTrajectoryOptions off = tubeOptions();
  off.jitterMm = 0.0;
  off.jitterDeg = 0.0;
  off.turnDegPerMm = 0.0;
  const std::vector<CameraPose> a = makeEndoscopeTrajectory(model, tubeOptions(), 7);
  const std::vector<CameraPose> b = makeEndoscopeTrajectory(model, off, 7);
  ASSERT_EQ(a.size(), b.size());
  for (size_t f = 0; f < a.size(); ++f)
  {
    EXPECT_EQ(a[f].centre, b[f].centre) << f;
    EXPECT_EQ(a[f].rotation, b[f].rotation) << f;
  }
}

TEST(EndoscopeTrajectory, JitterMovesTheCentresAndViewsOffTheSmoothPathByAboutTheSetAmount)
{
  // A wide tube, so that the tremor never pushes a centre into the clearance
  // and the jittered path starts where the smooth one does.
  const RegistrationModel model(fixtures::makeTube(7.0, 80.0));
  EndoscopeTrajectoryOptions o = tubeOptions();
  o.frames = 60;
  const std::vector<CameraPose> smooth = makeEndoscopeTrajectory(model, o, 4);
  o.jitterMm = 0.3;
  const std::vector<CameraPose> shaken = makeEndoscopeTrajectory(model, o, 4);
  const double offsetMm = rmsCentreDistanceMm(smooth, shaken);
  EXPECT_GT(offsetMm, 0.7 * o.jitterMm);
  EXPECT_LT(offsetMm, 1.3 * o.jitterMm);
  EXPECT_LT(rmsRotationDeg(smooth, shaken), 1e-9); // the views are the smooth path's
  for (const CameraPose& pose : shaken)
  {
    EXPECT_GE(model.locator().closestPoint(pose.centre).distanceMm, o.minClearanceMm - 1e-9);
  }

  o.jitterMm = 0.0;
  o.jitterDeg = 0.8;
  const std::vector<CameraPose> turned = makeEndoscopeTrajectory(model, o, 4);
  EXPECT_LT(rmsCentreDistanceMm(smooth, turned), 1e-12);
  const double angleDeg = rmsRotationDeg(smooth, turned);
  EXPECT_GT(angleDeg, 0.7 * o.jitterDeg);
  EXPECT_LT(angleDeg, 1.3 * o.jitterDeg);
}

TEST(EndoscopeTrajectory, ATurnCurvesThePathByTheRateTimesItsLength)
{
  const RegistrationModel model(fixtures::makeTube(7.0, 80.0));
  EndoscopeTrajectoryOptions o = tubeOptions();
  // No sway or wobble: the view is then the axis' own direction.
  o.swayAmplitudeMm = 0.0;
  o.viewSwayDeg = 0.0;
  o.turnDegPerMm = 1.0;
  for (std::uint64_t seed : { 1u, 2u })
  {
    const std::vector<CameraPose> path = makeEndoscopeTrajectory(model, o, seed);
    ASSERT_EQ(path.size(), 30u);
    const double lengthMm = (o.frames - 1) * o.stepMm;
    EXPECT_NEAR(angleDeg(path.front().viewDirection(), path.back().viewDirection()),
      o.turnDegPerMm * lengthMm, 0.05)
      << seed;
    for (size_t f = 0; f < path.size(); ++f)
    {
      EXPECT_TRUE(model.isInside(path[f].centre)) << f;
      EXPECT_GE(model.locator().closestPoint(path[f].centre).distanceMm, o.minClearanceMm - 1e-9);
      if (f > 0)
      {
        // An arc: each step as long as asked and turned by rate x step.
        const Eigen::Vector3d step = path[f].centre - path[f - 1].centre;
        EXPECT_NEAR(step.norm(), o.stepMm, 1e-3) << f;
        EXPECT_NEAR(angleDeg(path[f].viewDirection(), path[f - 1].viewDirection()),
          o.turnDegPerMm * o.stepMm, 1e-6)
          << f;
        EXPECT_LT(angleDeg(step, path[f].viewDirection()), o.turnDegPerMm * o.stepMm) << f;
      }
    }
  }
  // With the sway and wobble on, the turn is still there, within the wobble.
  o = tubeOptions();
  o.turnDegPerMm = 1.0;
  const std::vector<CameraPose> swaying = makeEndoscopeTrajectory(model, o, 3);
  EXPECT_NEAR(angleDeg(swaying.front().viewDirection(), swaying.back().viewDirection()),
    o.turnDegPerMm * (o.frames - 1) * o.stepMm, 2.0 * o.viewSwayDeg);
}

TEST(EndoscopeTrajectory, ATurnTooTightForThePassageFailsWithTheUsualError)
{
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeTrajectoryOptions o = tubeOptions();
  o.turnDegPerMm = 20.0;
  o.maxAttempts = 100;
  EXPECT_EQ(fixtures::errorMessageOf([&] { makeEndoscopeTrajectory(model, o, 1); }),
    "endoscope trajectory: found no passage turning 20 deg/mm of 22.5 mm with 2.0 mm clearance "
    "(and contours in view) in 100 attempts");
}

TEST(EndoscopeTrajectory, RefusesANegativeOrNonFiniteJitterOrTurn)
{
  const RegistrationModel model(fixtures::makeTube());
  EndoscopeTrajectoryOptions o = tubeOptions();
  o.jitterMm = -0.5;
  EXPECT_EQ(fixtures::errorMessageOf([&] { makeEndoscopeTrajectory(model, o, 1); }),
    "endoscope trajectory: the position jitter must be a finite number >= 0 mm, not -0.5");
  o = tubeOptions();
  o.jitterDeg = -1.0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "endoscope trajectory: the view jitter must be a finite number >= 0 degrees, not -1");
  o = tubeOptions();
  o.turnDegPerMm = std::numeric_limits<double>::infinity();
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "endoscope trajectory: the turn of the path must be a finite number >= 0 degrees per mm, not "
    "inf");
}
