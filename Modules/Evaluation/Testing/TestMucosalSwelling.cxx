#include "ErrorMessage.h"
#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/MucosalSwelling.h>
#include <vimlop/Evaluation/SimulatedWorld.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace vimlop;

namespace
{

/// A smooth passage of radius 8 mm running posteriorly (+y, LPS) from y = 0
/// to 60 mm, like a nasal cavity: the tube of TestMeshes turned from +z onto +y.
TriangleMesh passageAlongY()
{
  const TriangleMesh tube = fixtures::makeTube(8.0, 60.0, 0.0, 48, 120);
  std::vector<Eigen::Vector3d> v;
  for (const Eigen::Vector3d& p : tube.vertices())
  {
    v.emplace_back(p.x(), p.z(), -p.y()); // a rotation about x: orientation kept
  }
  return TriangleMesh(std::move(v), tube.faces());
}

double distanceToAxis(const Eigen::Vector3d& p)
{
  return std::hypot(p.x(), p.z());
}

std::string errorOf(const MucosalSwellingOptions& o)
{
  return fixtures::errorMessageOf([&] { o.validate(); });
}

} // namespace

TEST(MucosalSwelling, IsOffByDefaultAndThenMovesNothing)
{
  const TriangleMesh passage = passageAlongY();
  const SwollenSurface s = swellMucosa(passage, MucosalSwellingOptions());
  EXPECT_EQ(s.mesh.vertices(), passage.vertices());
  EXPECT_EQ(*std::max_element(s.displacementMm.begin(), s.displacementMm.end()), 0.0);
}

TEST(MucosalSwellingOnAPassage, MovesTheSideWallsOfItsFrontIntoTheAirByTheSetAmount)
{
  const TriangleMesh passage = passageAlongY();
  MucosalSwellingOptions o;
  o.swellingMm = 2.0;
  const SwollenSurface s = swellMucosa(passage, o);
  ASSERT_EQ(s.mesh.numberOfVertices(), passage.numberOfVertices());
  double largest = 0.0;
  for (int i = 0; i < passage.numberOfVertices(); ++i)
  {
    const Eigen::Vector3d& before = passage.vertices()[i];
    const Eigen::Vector3d& after = s.mesh.vertices()[i];
    const double moved = (after - before).norm();
    EXPECT_NEAR(moved, s.displacementMm[i], 1e-9);
    largest = std::max(largest, moved);
    const bool floorOrRoof = std::abs(before.x()) < 1.5 && before.y() > 10.0;
    if (before.y() > 60.0 * 0.6 + 5.0 || floorOrRoof)
    {
      // Behind the nasal cavity, and on its floor and roof (away from the
      // nostril's cap): untouched.
      EXPECT_EQ(moved, 0.0) << before.transpose();
    }
    if (before.y() > 3.0)
    {
      // Into the air or along the wall, never out of it (except at the sharp
      // rim of the nostril's flat cap, where the smoothing mixes in the
      // cap's normals: a real airway has no such rim).
      EXPECT_LE(distanceToAxis(after), distanceToAxis(before) + 1e-3) << before.transpose();
    }
  }
  EXPECT_NEAR(largest, 2.0, 1e-9);
  // The side walls at mid-height of the front are swollen by most of the amount.
  const Eigen::Vector3d side(8.0, 15.0, -1.5);
  int nearest = 0;
  for (int i = 0; i < passage.numberOfVertices(); ++i)
  {
    if ((passage.vertices()[i] - side).norm() < (passage.vertices()[nearest] - side).norm())
    {
      nearest = i;
    }
  }
  EXPECT_GT(s.displacementMm[nearest], 1.0);
  EXPECT_LT(distanceToAxis(s.mesh.vertices()[nearest]), 8.0 - 1.0);
  EXPECT_GT(s.swollenAreaMm2, 100.0);
}

TEST(MucosalSwelling, RefusesAMeshWithoutSideWallsAndBadSettings)
{
  // The tube along z has no wall facing left or right within its height band.
  MucosalSwellingOptions o;
  o.swellingMm = 1.0;
  o.lowFraction = 0.0;
  o.highFraction = 0.01;
  try
  {
    swellMucosa(fixtures::makeBox({ 0, 0, 0 }, { 10, 10, 10 }), o);
    ADD_FAILURE() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(),
      "mucosal swelling: no vertex of the airway lies in the nasal cavity's region (is the mesh a "
      "nasal airway in the CT frame, LPS?)");
  }
  MucosalSwellingOptions bad;
  bad.swellingMm = 6.0;
  EXPECT_EQ(errorOf(bad), "the mucosal swelling must lie in [0, 5] mm, not 6");
  bad = MucosalSwellingOptions();
  bad.lowFraction = 0.7;
  EXPECT_EQ(errorOf(bad), "the swelling region's low fraction must be below its high fraction");
  bad = MucosalSwellingOptions();
  bad.anteriorFraction = 1.5;
  EXPECT_EQ(errorOf(bad), "the swelling region's fractions must lie in [0, 1], not 1.5");
}

TEST(SimulatedWorldOfAMesh, IsTheMeshItselfWhenIdealAndSwellsOnlyTheTruth)
{
  const TriangleMesh passage = passageAlongY();
  SimulatedWorldOptions o;
  EXPECT_TRUE(o.isIdealWorld());
  const SimulatedWorld ideal = makeSimulatedWorld(passage, o);
  EXPECT_EQ(ideal.truth.vertices(), passage.vertices());
  EXPECT_EQ(ideal.model.vertices(), passage.vertices());
  EXPECT_EQ(ideal.truthToModel.maxMm, 0.0);

  o.swelling.swellingMm = 1.5;
  EXPECT_FALSE(o.isIdealWorld());
  const SimulatedWorld swollen = makeSimulatedWorld(passage, o);
  EXPECT_EQ(swollen.model.vertices(), passage.vertices());
  EXPECT_NEAR(swollen.swellingMaxMm, 1.5, 1e-9);
  // The truth lies off the model by up to the swelling (a little less: a
  // vertex moved along the normal comes closer to the neighbouring faces).
  EXPECT_GT(swollen.truthToModel.maxMm, 1.2);
  EXPECT_LE(swollen.truthToModel.maxMm, 1.5 + 1e-9);
}

TEST(SimulatedWorldOfAMesh, SaysThatAModelErrorOfTheCTNeedsTheCT)
{
  SimulatedWorldOptions o;
  o.segmentationOffsetHU = -100.0;
  try
  {
    makeSimulatedWorld(passageAlongY(), o);
    ADD_FAILURE() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(),
      "this model error (a deformation, a segmentation offset or a finer truth) needs the CT "
      "(--ct), not a mesh");
  }
  SimulatedWorldOptions bad;
  bad.anatomyDeformationMm = 25.0;
  try
  {
    bad.validate();
    ADD_FAILURE() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "the anatomy's deformation must lie in [0, 20] mm, not 25");
  }
}

TEST(MucosalSwellingOnANarrowPassage, ClosesItWithoutTheWallsCrossing)
{
  // A passage 2 mm wide swollen by 2 mm from each side: the walls move at
  // most 45 % of the free length ahead of them, so they meet near the axis
  // but never pass it.
  const TriangleMesh tube = fixtures::makeTube(1.0, 60.0, 0.0, 48, 120);
  std::vector<Eigen::Vector3d> v;
  for (const Eigen::Vector3d& p : tube.vertices())
  {
    v.emplace_back(p.x(), p.z(), -p.y());
  }
  const TriangleMesh passage(std::move(v), tube.faces());
  MucosalSwellingOptions o;
  o.swellingMm = 2.0;
  o.edgeMm = 1.0;
  const SwollenSurface s = swellMucosa(passage, o);
  double largest = 0.0;
  for (int i = 0; i < passage.numberOfVertices(); ++i)
  {
    const Eigen::Vector3d& before = passage.vertices()[i];
    if (before.y() < 3.0 || distanceToAxis(before) < 0.99)
    {
      continue; // the nostril's cap
    }
    largest = std::max(largest, s.displacementMm[i]);
    EXPECT_LE(s.displacementMm[i], 0.45 * 2.0 + 0.1) << before.transpose();
    // Still on its own side of the axis: the wall did not cross it.
    const Eigen::Vector3d& after = s.mesh.vertices()[i];
    EXPECT_GT(after.x() * before.x() + after.z() * before.z(), 0.0) << before.transpose();
  }
  EXPECT_GT(largest, 0.5);
  MucosalSwellingOptions bad;
  bad.maxFreeFraction = 0.6;
  EXPECT_EQ(errorOf(bad), "the swelling's share of the free length must lie in (0, 0.5), not 0.6");
}
