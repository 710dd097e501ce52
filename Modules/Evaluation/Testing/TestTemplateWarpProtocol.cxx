#include "AirwayPhantom.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/TemplateWarpProtocol.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

using namespace vimlop;
using fixtures::HeadPhantom;

namespace
{

/// P4 on the phantom head: a small field, finer levels than a CT needs.
TemplateWarpProtocolOptions phantomRun()
{
  TemplateWarpProtocolOptions o;
  o.maxDisplacementMm = 3.0;
  o.controlSpacingMm = 24.0;
  o.noiseHU = 10.0;
  o.seed = 3;
  o.runElastix = false;
  o.registration.marginMm = 10.0;
  o.registration.affineLevelSpacingMm = { 2.0, 1.0 };
  o.registration.synLevelSpacingMm = { 2.0, 1.0 };
  o.registration.synIterations = { 30, 20 };
  return o;
}

std::string errorOf(const TemplateWarpProtocolOptions& o)
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

TEST(TemplateWarpProtocol, BringsThePhantomsAirwayOntoAKnownDeformationOfIt)
{
  int last = -1;
  bool monotone = true;
  const TemplateWarpProtocolReport r = runTemplateWarpProtocol(HeadPhantom::make(), phantomRun(),
    [&](const std::string&, int done, int total)
    {
      EXPECT_EQ(total, 1000);
      monotone = monotone && done >= last;
      last = done;
      return true;
    });
  EXPECT_TRUE(monotone);
  EXPECT_EQ(last, 1000);
  EXPECT_GT(r.vertices, 100u);
  EXPECT_GT(r.beforeRegistration.meanMm, 1.0);
  EXPECT_LT(r.errors.meanMm, 0.5);
  EXPECT_LT(r.errors.p95Mm, 1.0);
  EXPECT_LE(r.errors.p95Mm, r.errors.maxMm);
  EXPECT_GT(r.finalCorrelation, 0.9);
  EXPECT_FALSE(r.elastix);
  EXPECT_EQ(r.elastixStatus, "not run (--no-elastix)");

  const nlohmann::json j = r.toJson();
  EXPECT_EQ(j["mean_mm"].get<double>(), r.errors.meanMm);
  EXPECT_EQ(j["before_registration"]["mean_mm"].get<double>(), r.beforeRegistration.meanMm);
  EXPECT_EQ(j["registration"]["correlation"]["final"].get<double>(), r.finalCorrelation);
  EXPECT_TRUE(j["elastix"].is_null());
}

TEST(TemplateWarpProtocol, ScoresAScannedAndEditedPatientAndTheCarriedCanonicalPoses)
{
  // Thicker slices, the head moved in the scanner and two local edits: the
  // truth includes the move, so "before" grows by it, the vertices near the
  // edits are left out, and the registration still finds the rest.
  TemplateWarpProtocolOptions o = phantomRun();
  o.edits.count = 2;
  o.edits.radiusMm = 4.0;
  o.edits.depthMm = 1.0;
  o.scan.sliceSpacingMm = 1.5;
  o.scan.rotationDeg = 4.0;
  o.scan.shiftMm = { 3.0, 0.0, -2.0 };
  const TemplateWarpProtocolReport scanned =
    runTemplateWarpProtocol(HeadPhantom::make(), o, nullptr);
  const TemplateWarpProtocolReport plain =
    runTemplateWarpProtocol(HeadPhantom::make(), phantomRun(), nullptr);
  std::printf("phantom P4: plain %.2f mm (before %.2f), scanned %.2f mm (before %.2f); poses "
              "%zu: %.2f mm, %.2f deg\n",
    plain.errors.meanMm, plain.beforeRegistration.meanMm, scanned.errors.meanMm,
    scanned.beforeRegistration.meanMm, scanned.poseErrors.poses, scanned.poseErrors.meanMm,
    scanned.poseErrors.meanDeg);
  EXPECT_GT(scanned.beforeRegistration.meanMm, plain.beforeRegistration.meanMm + 1.0);
  EXPECT_LT(scanned.errors.meanMm, 0.6);
  ASSERT_EQ(scanned.edits.size(), 2u);
  EXPECT_GT(scanned.editedVoxels, 0u);
  EXPECT_GT(scanned.verticesNearEdits, 0u);
  EXPECT_LT(scanned.verticesNearEdits, scanned.vertices / 2);
  EXPECT_EQ(plain.verticesNearEdits, 0u);
  EXPECT_GT(scanned.poseErrors.poses, 0u);
  EXPECT_EQ(scanned.poseErrors.poses + scanned.posesNearEdits, plain.poseErrors.poses);
  EXPECT_LT(scanned.poseErrors.meanMm, 1.0);
  // Less than the head's turn, which a pose carried without its rotation keeps.
  EXPECT_LT(scanned.poseErrors.meanDeg, o.scan.rotationDeg);
  EXPECT_LE(scanned.poseErrors.meanDeg, scanned.poseErrors.maxDeg);
  EXPECT_LE(scanned.poseErrors.p95Deg, scanned.poseErrors.maxDeg);
  EXPECT_LE(scanned.poseErrors.p95Mm, scanned.poseErrors.maxMm);
  // The worst pose is a canonical pose of the template: within the bounds
  // of its air spaces (the passage, the nostril, the sinus; 1 mm voxels from
  // the origin), off the walls, and no farther from them than half the
  // widest space.
  const std::array<int, 6> air{ 28, 43, 38, 50, 0, 24 };
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_GE(scanned.poseErrors.maxDegAtMm[a], air[2 * a]) << a;
    EXPECT_LE(scanned.poseErrors.maxDegAtMm[a], air[2 * a + 1] + 1) << a;
  }
  EXPECT_GT(scanned.poseErrors.maxDegWallDistanceMm, 0.0);
  EXPECT_LT(scanned.poseErrors.maxDegWallDistanceMm, 7.0);
  const nlohmann::json j = scanned.toJson();
  EXPECT_EQ(j["scan"]["slice_spacing_mm"].get<double>(), 1.5);
  EXPECT_EQ(j["edits"]["placed"][1]["kind"].get<std::string>(), "shrink");
  EXPECT_EQ(j["edits"]["placed"][1]["site"].get<std::string>(), "wall");
  EXPECT_EQ(j["edits"]["sites"].get<std::string>(), "random");
  EXPECT_EQ(j["edits"]["vertices_left_out"].get<std::size_t>(), scanned.verticesNearEdits);
  EXPECT_EQ(j["canonical_poses"]["poses"].get<std::size_t>(), scanned.poseErrors.poses);
  EXPECT_EQ(j["canonical_poses"]["p95_deg"].get<double>(), scanned.poseErrors.p95Deg);
  EXPECT_EQ(j["canonical_poses"]["max_deg_wall_distance_mm"].get<double>(),
    scanned.poseErrors.maxDegWallDistanceMm);
  // The orientation turned by the walls: every pose of the phantom has walls
  // within 15 mm.
  EXPECT_EQ(scanned.poseErrors.byWalls.poses, scanned.poseErrors.poses);
  EXPECT_LE(scanned.poseErrors.byWalls.meanDeg, scanned.poseErrors.byWalls.p95Deg);
  EXPECT_LE(scanned.poseErrors.byWalls.p95Deg, scanned.poseErrors.byWalls.maxDeg);
  EXPECT_LT(scanned.poseErrors.byWalls.meanDeg, o.scan.rotationDeg);
  EXPECT_EQ(scanned.truthWallsAgainstJacobian.poses, scanned.poseErrors.poses);
  EXPECT_EQ(
    j["canonical_poses"]["by_walls"]["max_deg"].get<double>(), scanned.poseErrors.byWalls.maxDeg);
  EXPECT_EQ(j["canonical_poses"]["truth_by_walls_against_jacobian"]["mean_deg"].get<double>(),
    scanned.truthWallsAgainstJacobian.meanDeg);
  EXPECT_NE(scanned.summaryText().find(" canonical poses: mean "), std::string::npos);
  EXPECT_NE(scanned.summaryText().find("; turned by the walls: mean "), std::string::npos);
}

TEST(TemplateWarpProtocol, RefusesANonPositiveDisplacementNegativeNoiseOrNoElastixFolder)
{
  TemplateWarpProtocolOptions o = phantomRun();
  o.maxDisplacementMm = 0.0;
  EXPECT_EQ(errorOf(o), "--max-displacement-mm must be positive");
  o = phantomRun();
  o.noiseHU = -1.0;
  EXPECT_EQ(errorOf(o), "--noise-hu must not be negative");
  o = phantomRun();
  o.runElastix = true;
  EXPECT_EQ(errorOf(o), "P4: elastix needs a work folder");
  o = phantomRun();
  o.scan.pixelSpacingMm = 9.0;
  EXPECT_EQ(errorOf(o), "patient scan: pixel spacing (0 or 0.1-5 mm) 9 is out of range");
  o = phantomRun();
  o.edits.count = -1;
  EXPECT_EQ(errorOf(o), "anatomy edits: count (0-20) -1 is out of range");
}
