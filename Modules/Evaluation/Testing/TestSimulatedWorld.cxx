#include "CraniumAirway.h"
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Evaluation/SimulatedWorld.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <gtest/gtest.h>

using namespace vimlop;

// The worlds of the bundled head CT (Debian's invesalius-examples).

TEST(SimulatedWorldOfTheCranium, IsTheAirwayOfVimlopSegmentWhenIdeal)
{
  const SimulatedWorld world =
    makeSimulatedWorld(readCTVolume(fixtures::craniumPath()), SimulatedWorldOptions(), {});
  const TriangleMesh segmented = fixtures::craniumAirwayMesh();
  EXPECT_EQ(world.model.vertices(), segmented.vertices());
  EXPECT_EQ(world.truth.vertices(), segmented.vertices());
  EXPECT_TRUE(world.canonicalPosesCT.empty());
}

TEST(SimulatedWorldOfTheCranium, SegmentsTheTruthFinerAndAtAnotherThreshold)
{
  SimulatedWorldOptions o;
  o.segmentationOffsetHU = -100.0; // -500 HU: less counts as air
  o.truthTriangles = 0;
  const SimulatedWorld world = makeSimulatedWorld(readCTVolume(fixtures::craniumPath()), o, {});
  EXPECT_EQ(world.model.numberOfFaces(), 30000);
  // The full iso-surface of this CT: about 54000 triangles.
  EXPECT_GT(2 * world.truth.numberOfFaces(), 3 * world.model.numberOfFaces());
  // Partial-volume voxels between -500 and -400 HU move the wall by a
  // fraction of a voxel (0.5-1 mm here); a sinus may come or go whole.
  EXPECT_GT(world.truthToModel.medianMm, 0.05);
  EXPECT_LT(world.truthToModel.medianMm, 1.0);
}

TEST(SimulatedWorldOfTheCranium, WarpsTheTemplateToADeformedPatientAndCarriesItsPoses)
{
  SimulatedWorldOptions o;
  o.anatomyDeformationMm = 5.0;
  const SimulatedWorld world = makeSimulatedWorld(readCTVolume(fixtures::craniumPath()), o, {});
  // The model is the template's airway warped by our registration: off the
  // patient's own airway by about P4's error (0.4-0.5 mm mean), far less
  // than the 5 mm of the deformation.
  EXPECT_GT(world.warpErrorMeanMm, 0.05);
  EXPECT_LT(world.warpErrorMeanMm, 1.5);
  EXPECT_GT(world.truthToModel.meanMm, 0.05);
  EXPECT_LT(world.truthToModel.medianMm, 1.5);
  // The template's canonical poses, carried over, lie mostly in the patient's airway.
  ASSERT_GT(world.canonicalPosesCT.size(), 100u);
  const RegistrationModel truth = makeEmbreeRegistrationModel(world.truth);
  std::size_t inside = 0;
  for (const CameraPose& pose : world.canonicalPosesCT)
  {
    inside += truth.isInside(pose.centre) ? 1 : 0;
  }
  EXPECT_GT(inside, 9 * world.canonicalPosesCT.size() / 10);
}
