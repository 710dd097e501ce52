#include "AirwayPhantom.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/OrientNormalsIntoAir.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Imaging/AirwaySurface.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/ModelLoading.h>
#include <vimlop/Imaging/PolyDataConversion.h>

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <cmath>

using namespace vimlop;

namespace
{

struct Grid
{
  std::string name;
  std::array<double, 3> spacing;
  std::array<double, 3> origin;
  std::array<double, 9> direction;
};

void PrintTo(const Grid& grid, std::ostream* os)
{
  *os << grid.name;
}

std::array<double, 9> rowMajor(const Eigen::Matrix3d& m)
{
  return { m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2) };
}

double voxelVolume(const CTVolume& label)
{
  double count = 0.0;
  for (float v : label.intensities)
  {
    count += v != 0.0f ? 1.0 : 0.0;
  }
  return count * label.spacingMm[0] * label.spacingMm[1] * label.spacingMm[2];
}

} // namespace

class AirwaySurfaceOnGrids : public ::testing::TestWithParam<Grid>
{
};

// A ball of air on grids with identity, reflected (InVesalius) and oblique
// directions: the surface lands on the ball in the CT frame and its normals
// point into the ball, i.e. into the air.
TEST_P(AirwaySurfaceOnGrids, LiesOnTheBallWithNormalsIntoTheAir)
{
  const Grid& grid = GetParam();
  // Put the ball in the middle of the grid, wherever the direction sends it.
  const std::array<int, 3> dims{ 30, 28, 22 };
  CTVolume probe = fixtures::emptyVolume(dims, grid.spacing);
  probe.originMm = grid.origin;
  probe.direction = grid.direction;
  const std::array<double, 3> centre = probe.indexToPhysical({ 14.5, 13.2, 10.7 });
  const double radius = 9.0;
  const CTVolume label =
    fixtures::sphereLabel(dims, grid.spacing, grid.origin, grid.direction, centre, radius);

  AirwaySurfaceOptions options;
  options.targetTriangles = 2000;
  const AirwaySurface s = AirwaySurface::compute(label, options);
  ASSERT_TRUE(s.surface);
  EXPECT_NEAR(s.triangles, 2000, 20);
  EXPECT_EQ(s.boundaryEdges, 0);
  EXPECT_EQ(s.nonManifoldEdges, 0);
  EXPECT_EQ(s.droppedPieces, 0);
  EXPECT_NEAR(s.enclosedVolumeMm3, voxelVolume(label), 0.05 * voxelVolume(label));
  EXPECT_NEAR(s.areaMm2, 4.0 * M_PI * radius * radius, 0.08 * 4.0 * M_PI * radius * radius);

  const TriangleMesh mesh = toTriangleMesh(s.surface);
  const Eigen::Vector3d c(centre[0], centre[1], centre[2]);
  const double voxel = *std::max_element(grid.spacing.begin(), grid.spacing.end());
  for (const Eigen::Vector3d& v : mesh.vertices())
  {
    EXPECT_NEAR((v - c).norm(), radius, 0.8 * voxel);
  }
  vtkDataArray* cellNormals = s.surface->GetCellData()->GetNormals();
  vtkDataArray* pointNormals = s.surface->GetPointData()->GetNormals();
  ASSERT_NE(cellNormals, nullptr);
  ASSERT_NE(pointNormals, nullptr);
  int facing = 0;
  int within60 = 0;
  for (int f = 0; f < mesh.numberOfFaces(); ++f)
  {
    // The winding (TriangleMesh) and the stored normals agree...
    const Eigen::Vector3d stored(cellNormals->GetTuple3(f));
    EXPECT_GT(stored.dot(mesh.faceNormals()[f]), 0.999);
    // ... and face the centre, but for the odd triangle that decimation folds.
    const double cosine = mesh.faceNormals()[f].dot((c - mesh.faceCentroid(f)).normalized());
    facing += cosine > 0.0 ? 1 : 0;
    within60 += cosine > 0.5 ? 1 : 0;
  }
  EXPECT_GE(facing, mesh.numberOfFaces() - 2);
  EXPECT_GT(within60, 0.99 * mesh.numberOfFaces());
  for (int p = 0; p < mesh.numberOfVertices(); ++p)
  {
    const Eigen::Vector3d n(pointNormals->GetTuple3(p));
    EXPECT_GT(n.dot((c - mesh.vertices()[p]).normalized()), 0.5);
  }

  // What compute() writes, a loader reads as it is: the producer and the
  // loaders' rule (orientNormalsIntoAir) agree on the side of the air.
  const std::string path =
    std::string(VIMLOP_TEST_OUTPUT_DIR) + "/airway-surface-" + grid.name + ".vtp";
  writePolyData(s.surface, path);
  const TriangleMesh loaded = loadAirwayMesh(path);
  ASSERT_EQ(loaded.numberOfFaces(), mesh.numberOfFaces());
  for (int f = 0; f < mesh.numberOfFaces(); ++f)
  {
    ASSERT_EQ(loaded.faces()[f], mesh.faces()[f]) << "face " << f;
  }
  EXPECT_LT(loaded.signedVolume(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Directions, AirwaySurfaceOnGrids,
  ::testing::Values(
    Grid{ "identity", { 1.0, 1.0, 1.0 }, { 0, 0, 0 }, { 1, 0, 0, 0, 1, 0, 0, 0, 1 } },
    Grid{ "inv3", { 0.957, 0.957, 1.5 }, { 0.0, 244.0, 0.0 }, { 1, 0, 0, 0, -1, 0, 0, 0, 1 } },
    Grid{ "oblique", { 0.8, 1.1, 1.3 }, { -40.0, 12.0, 300.0 },
      rowMajor(rotationFromVector(Eigen::Vector3d(0.3, -0.5, 0.9))) },
    Grid{ "mirrored_oblique", { 1.2, 0.9, 1.0 }, { 5.0, -7.0, 11.0 },
      rowMajor(rotationFromVector(Eigen::Vector3d(-0.7, 0.2, 0.4)) *
        Eigen::Vector3d(1, 1, -1).asDiagonal()) }),
  [](const auto& info) { return info.param.name; });

TEST(AirwaySurface, KeepsTheLargestPieceAndClosesAtTheVolumeBorder)
{
  // A slab of air that touches two faces of the volume, and a small blob.
  CTVolume label = fixtures::emptyVolume({ 24, 20, 16 });
  std::fill(label.intensities.begin(), label.intensities.end(), 0.0f);
  fixtures::paint(label, 1.0f,
    [](int i, int j, int k) {
      return fixtures::inBox(i, j, k, { 0, 12, 4, 15, 0, 9 });
    });
  fixtures::paint(label, 1.0f,
    [](int i, int j, int k) {
      return fixtures::inBox(i, j, k, { 18, 20, 15, 17, 12, 14 });
    });
  AirwaySurfaceOptions options;
  options.targetTriangles = 0; // keep the iso-surface as it is
  options.smoothingIterations = 0;
  const AirwaySurface s = AirwaySurface::compute(label, options);
  EXPECT_EQ(s.droppedPieces, 1);
  EXPECT_GT(s.droppedTriangleFraction, 0.0);
  EXPECT_LT(s.droppedTriangleFraction, 0.2);
  EXPECT_EQ(s.boundaryEdges, 0);
  // Without smoothing, the iso-surface at 0.5 of a box of 13 x 12 x 10
  // voxels runs half a voxel outside the voxel centres, so it encloses the
  // voxels' volume less the prisms cut off along the 12 edges (a right
  // triangle of legs 0.5 across, 140 voxels of edge length in all); the
  // faces on the volume's border are closed by the padding.
  EXPECT_NEAR(s.enclosedVolumeMm3, 13.0 * 12.0 * 10.0 - 140 * 0.125, 1.0);
  double bounds[6];
  s.surface->GetBounds(bounds);
  EXPECT_NEAR(bounds[0], -0.5, 1e-9);
  EXPECT_NEAR(bounds[4], -0.5, 1e-9);
  EXPECT_NEAR(bounds[1], 12.5, 1e-9);
}

TEST(AirwaySurface, SaysWhenTheTriangleTargetIsAboveWhatTheIsoSurfaceHas)
{
  CTVolume label = fixtures::emptyVolume({ 16, 16, 16 });
  std::fill(label.intensities.begin(), label.intensities.end(), 0.0f);
  fixtures::paint(label, 1.0f,
    [](int i, int j, int k) {
      return fixtures::inBox(i, j, k, { 3, 12, 3, 12, 3, 12 });
    });
  AirwaySurfaceOptions options;
  options.smoothingIterations = 0;
  options.targetTriangles = 100;
  const AirwaySurface decimated = AirwaySurface::compute(label, options);
  EXPECT_GT(decimated.isoSurfaceTriangles, 100);
  EXPECT_LE(decimated.triangles, decimated.isoSurfaceTriangles);
  EXPECT_TRUE(decimated.warnings().empty());

  options.targetTriangles = 1000000;
  const AirwaySurface kept = AirwaySurface::compute(label, options);
  EXPECT_EQ(kept.triangles, kept.isoSurfaceTriangles);
  ASSERT_EQ(kept.warnings().size(), 1u);
  EXPECT_EQ(kept.warnings()[0],
    "asked for 1000000 triangles, but the iso-surface of the airway has only " +
      std::to_string(kept.isoSurfaceTriangles) +
      ": it is kept undecimated (a finer surface needs a CT with smaller voxels)");
}

// An open surface (here the ball's surface with a cap cut off) encloses
// nothing, so the loaders' rule keeps whatever face order it has; the label
// knows the air side, and orientIntoAir() turns the faces into the ball
// either way. A closed surface follows the loaders' rule.
TEST(AirwaySurface, OrientsAnOpenSurfaceByTheLabel)
{
  const std::array<int, 3> dims{ 30, 28, 22 };
  const std::array<double, 3> spacing{ 0.9, 1.1, 1.2 };
  const std::array<double, 9> reflected{ 1, 0, 0, 0, -1, 0, 0, 0, 1 };
  CTVolume probe = fixtures::emptyVolume(dims, spacing);
  probe.direction = reflected;
  const std::array<double, 3> centre = probe.indexToPhysical({ 14.5, 13.2, 10.7 });
  const CTVolume label =
    fixtures::sphereLabel(dims, spacing, { 0.0, 0.0, 0.0 }, reflected, centre, 9.0);
  AirwaySurfaceOptions options;
  options.targetTriangles = 2000;
  const TriangleMesh closed = toTriangleMesh(AirwaySurface::compute(label, options).surface);
  ASSERT_EQ(closed.numberOfBoundaryEdges(), 0);
  EXPECT_EQ(AirwaySurface::orientIntoAir(closed.flipped(), label).faces(), closed.faces());
  EXPECT_EQ(AirwaySurface::orientIntoAir(closed, label).faces(), closed.faces());

  std::vector<Eigen::Vector3i> kept;
  for (int f = 0; f < closed.numberOfFaces(); ++f)
  {
    if (closed.faceCentroid(f).z() < centre[2] + 4.0)
    {
      kept.push_back(closed.faces()[f]);
    }
  }
  const TriangleMesh open(closed.vertices(), kept);
  ASSERT_GT(open.numberOfBoundaryEdges(), 0);
  const Eigen::Vector3d c(centre[0], centre[1], centre[2]);
  const auto facingCentre = [&c](const TriangleMesh& m)
  {
    int facing = 0;
    for (int f = 0; f < m.numberOfFaces(); ++f)
    {
      facing += m.faceNormals()[f].dot(c - m.faceCentroid(f)) > 0.0 ? 1 : 0;
    }
    return facing;
  };
  ASSERT_GT(facingCentre(open), 0.99 * open.numberOfFaces());
  // The loaders' rule cannot tell: it keeps the outward faces.
  EXPECT_EQ(orientNormalsIntoAir(open.flipped()).faces(), open.flipped().faces());
  EXPECT_EQ(AirwaySurface::orientIntoAir(open.flipped(), label).faces(), open.faces());
  EXPECT_EQ(AirwaySurface::orientIntoAir(open, label).faces(), open.faces());
}

TEST(AirwaySurface, BadInputGetsOneLineErrors)
{
  CTVolume empty = fixtures::emptyVolume({ 8, 8, 8 });
  std::fill(empty.intensities.begin(), empty.intensities.end(), 0.0f);
  AirwaySurfaceOptions options;
  try
  {
    AirwaySurface::compute(empty, options);
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "the airway label is empty");
  }
  CTVolume flat = fixtures::emptyVolume({ 8, 8, 1 });
  EXPECT_THROW(AirwaySurface::compute(flat, options), Error);
  empty.intensities[100] = 1.0f;
  options.targetTriangles = 2;
  EXPECT_THROW(AirwaySurface::compute(empty, options), Error);
  options.targetTriangles = 100;
  options.smoothingPassBand = 0.0;
  EXPECT_THROW(AirwaySurface::compute(empty, options), Error);
}
