#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Rendering/EndoscopeTrajectory.h>

#include <gtest/gtest.h>

#include <cmath>

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
