// P1 faithful to a wrong model (issue 14, item 4): data drawn from another
// surface than the model, a misspecified noise model, a wrong start scale.
#include "ErrorMessage.h"
#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Evaluation/SyntheticDataSurface.h>
#include <vimlop/Evaluation/SyntheticProtocol.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace vimlop;

namespace
{

/// Two small trials of V-IMLOP and IMLP on a cavity built in memory.
SyntheticProtocolOptions smallRun()
{
  SyntheticProtocolOptions o;
  o.trials = 2;
  o.synthetic.points = 400;
  o.methods = { "vimlop", "imlp" };
  return o;
}

/// `mesh` with every vertex moved `offsetMm` along its normal (into the air).
TriangleMesh shiftedAlongNormals(const TriangleMesh& mesh, double offsetMm)
{
  std::vector<Eigen::Vector3d> vertices = mesh.vertices();
  for (size_t i = 0; i < vertices.size(); ++i)
  {
    vertices[i] += offsetMm * mesh.vertexNormals()[i];
  }
  return TriangleMesh(std::move(vertices), mesh.faces());
}

/// Mean distance of a trial's points, at the true transform, to the model's surface, mm.
double meanTruthDistanceMm(const RegistrationModel& model, const SyntheticTrial& trial)
{
  double sum = 0.0;
  for (const Eigen::Vector3d& p : trial.data.points)
  {
    sum += model.locator().closestPoint(trial.truthSfmToCT.apply(p)).distanceMm;
  }
  return sum / static_cast<double>(trial.data.points.size());
}

} // namespace

TEST(SyntheticDataSurface, DataDrawnFromTheModelItselfGiveTodaysFiguresBitForBit)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  const SyntheticProtocolReport today = runSyntheticProtocol(mesh, smallRun(), {});
  SyntheticProtocolOptions o = smallRun();
  o.dataSurface = mesh; // a second copy, with its own scene
  o.assumedNoiseScale = 1.0;
  o.synthetic.startScaleError = 0.0;
  const SyntheticProtocolReport same = runSyntheticProtocol(mesh, o, {});
  ASSERT_EQ(today.methods.size(), same.methods.size());
  for (size_t m = 0; m < today.methods.size(); ++m)
  {
    EXPECT_EQ(today.methods[m].treMeanMm, same.methods[m].treMeanMm) << m;
    EXPECT_EQ(today.methods[m].cameraPositionMedianMm, same.methods[m].cameraPositionMedianMm);
    EXPECT_EQ(today.methods[m].residualMedianMm, same.methods[m].residualMedianMm);
  }
  EXPECT_EQ(same.toJson()["model_error"]["data_surface_triangles"], mesh.numberOfFaces());
  EXPECT_EQ(today.toJson()["model_error"]["data_surface"], "model");
  EXPECT_EQ(today.toJson()["model_error"]["data_surface_triangles"], 0);
}

TEST(SyntheticDataSurface, DataFromASurfaceHalfAMillimetreOffTheModelLeaveLargerResiduals)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  const TriangleMesh shifted = shiftedAlongNormals(mesh, 0.5);
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  const RegistrationModel data = makeEmbreeRegistrationModel(shifted);
  SyntheticOptions o = SyntheticOptions::paper();
  o.points = 400;
  const SyntheticTrial onModel = makeSyntheticTrial(model, o, 11);
  const SyntheticTrial offModel = makeSyntheticTrial(model, data, o, 11);
  // At the truth, the points lie further from the model: by 0.5 mm without
  // noise, by less with it (the noise alone already moves them both ways).
  EXPECT_GT(meanTruthDistanceMm(model, offModel), meanTruthDistanceMm(model, onModel) + 0.1);
  EXPECT_EQ(offModel.data.points.size(), onModel.data.points.size());

  // And after registration, the residuals of both methods grow, less than
  // that: the registration takes up part of the offset in its scale and
  // translation.
  SyntheticProtocolOptions p = smallRun();
  const SyntheticProtocolReport ideal = runSyntheticProtocol(mesh, p, {});
  p.dataSurface = shifted;
  const SyntheticProtocolReport wrong = runSyntheticProtocol(mesh, p, {});
  for (size_t m = 0; m < ideal.methods.size(); ++m)
  {
    EXPECT_GT(wrong.methods[m].residualMedianMm, ideal.methods[m].residualMedianMm + 0.03)
      << ideal.methods[m].method;
  }
}

TEST(SyntheticDataSurface, AWrongStartScaleIsRecoveredWithinTheScaleBounds)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  SyntheticOptions o = SyntheticOptions::paper();
  o.points = 400;
  o.startScaleError = 0.15;
  const SyntheticTrial trial = makeSyntheticTrial(model, o, 3);
  EXPECT_DOUBLE_EQ(trial.initialSfmToCT.scale, 1.15);
  EXPECT_DOUBLE_EQ(trial.truthSfmToCT.scale, 1.0);

  SyntheticProtocolOptions p = smallRun();
  p.methods = { "vimlop" };
  p.synthetic.startScaleError = 0.15;
  const SyntheticProtocolReport r = runSyntheticProtocol(mesh, p, {});
  EXPECT_LT(r.methods[0].treMedianMm, 0.5);
  EXPECT_DOUBLE_EQ(r.methods[0].successRate, 1.0);
  EXPECT_EQ(r.toJson()["model_error"]["start_scale_error"].get<double>(), 0.15);
}

TEST(SyntheticDataSurface, AMisspecifiedNoiseModelChangesTheResult)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  SyntheticProtocolOptions p = smallRun();
  const SyntheticProtocolReport truth = runSyntheticProtocol(mesh, p, {});
  p.assumedNoiseScale = 4.0;
  const SyntheticProtocolReport wrong = runSyntheticProtocol(mesh, p, {});
  for (size_t m = 0; m < truth.methods.size(); ++m)
  {
    EXPECT_NE(truth.methods[m].treMeanMm, wrong.methods[m].treMeanMm) << truth.methods[m].method;
  }
  EXPECT_EQ(wrong.toJson()["model_error"]["assumed_noise_scale"].get<double>(), 4.0);
}

TEST(SyntheticDataSurface, ADeformedSurfaceMovesByAtMostTheFieldsLargestDisplacement)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  SyntheticDataSurfaceOptions o;
  o.surface = SyntheticDataSurface::Deformed;
  o.deformationControlSpacingMm = 10.0; // a cavity of a few cm: a few control points across
  const SyntheticSurfaces surfaces = makeSyntheticSurfaces(mesh, o);
  EXPECT_EQ(surfaces.model.vertices(), mesh.vertices());
  ASSERT_EQ(surfaces.data.numberOfVertices(), mesh.numberOfVertices());
  EXPECT_EQ(surfaces.data.faces(), mesh.faces());
  double largest = 0.0;
  for (int i = 0; i < mesh.numberOfVertices(); ++i)
  {
    largest = std::max(largest, (surfaces.data.vertices()[i] - mesh.vertices()[i]).norm());
  }
  EXPECT_LE(largest, o.deformationMm + 1e-6);
  EXPECT_GT(largest, 0.5 * o.deformationMm);
  EXPECT_TRUE(makeSyntheticSurfaces(mesh, SyntheticDataSurfaceOptions()).data.vertices().empty());
  EXPECT_EQ(o.toJson()["data_deformation_mm"].get<double>(), 0.5);
}

TEST(SyntheticDataSurface, RefusesBadValuesWithClearMessages)
{
  EXPECT_EQ(fixtures::errorMessageOf([] { syntheticDataSurfaceFromString("coarser"); }),
    "unknown data surface 'coarser' (expected model, finer, threshold or deformed)");
  EXPECT_EQ(syntheticDataSurfaceFromString("threshold"), SyntheticDataSurface::Threshold);
  SyntheticDataSurfaceOptions d;
  d.surface = SyntheticDataSurface::Finer;
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  EXPECT_EQ(fixtures::errorMessageOf([&] { makeSyntheticSurfaces(mesh, d); }),
    "the data surface 'finer' needs the CT (--ct), not a mesh");
  d = SyntheticDataSurfaceOptions();
  d.deformationMm = -0.5;
  EXPECT_EQ(fixtures::errorMessageOf([&] { d.validate(); }),
    "the data surface's deformation must lie in (0, 20] mm, not -0.5");
  d = SyntheticDataSurfaceOptions();
  d.offsetHU = 400.0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { d.validate(); }),
    "the data surface's threshold offset must lie in [-300, 300] HU, not 400");

  SyntheticProtocolOptions p = smallRun();
  p.assumedNoiseScale = 0.0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { validateSyntheticProtocolOptions(p); }),
    "P1: the assumed noise scale must be a finite number > 0, not 0");
  p = smallRun();
  p.synthetic.startScaleError = 0.3;
  EXPECT_EQ(fixtures::errorMessageOf([&] { runSyntheticProtocol(mesh, p, {}); }),
    "P1: the start's scale 1 + 0.3 lies outside the scale bounds [0.8, 1.25]");
  SyntheticOptions o = SyntheticOptions::paper();
  o.startScaleError = -1.0;
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  EXPECT_EQ(fixtures::errorMessageOf([&] { makeSyntheticTrial(model, o, 1); }),
    "synthetic experiment: the start's scale error must be a finite number above -1, not -1");
}
