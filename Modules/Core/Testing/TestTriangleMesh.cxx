#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/TriangleMesh.h>

#include <Eigen/Dense>

#include <gtest/gtest.h>

using namespace vimlop;

TEST(TriangleMesh, BoxTopologyAndGeometry)
{
  const TriangleMesh box = fixtures::makeBox({ 0, 0, 0 }, { 2, 3, 4 });
  EXPECT_EQ(box.numberOfVertices(), 8);
  EXPECT_EQ(box.numberOfFaces(), 12);
  // A closed triangulated surface with F faces has 3F/2 edges.
  EXPECT_EQ(box.edges().size(), 18u);
  EXPECT_EQ(box.numberOfBoundaryEdges(), 0);
  EXPECT_EQ(box.numberOfNonManifoldEdges(), 0);
  EXPECT_NEAR(box.totalArea(), 2 * (2 * 3 + 3 * 4 + 2 * 4), 1e-12);
  EXPECT_LT((box.bounds().col(1) - Eigen::Vector3d(2, 3, 4)).norm(), 1e-15);
  // Normals into the cavity: negative signed volume; flipped: positive.
  EXPECT_NEAR(box.signedVolume(), -24.0, 1e-12);
  EXPECT_NEAR(box.flipped().signedVolume(), 24.0, 1e-12);
}

TEST(TriangleMesh, NormalsPointInwardForCavities)
{
  const Eigen::Vector3d centre(1.0, 2.0, 3.0);
  const TriangleMesh sphere = fixtures::makeSphere(5.0, 2, centre);
  for (int f = 0; f < sphere.numberOfFaces(); ++f)
  {
    const Eigen::Vector3d towardCentre = (centre - sphere.faceCentroid(f)).normalized();
    EXPECT_GT(sphere.faceNormals()[f].dot(towardCentre), 0.99);
    EXPECT_NEAR(sphere.faceNormals()[f].norm(), 1.0, 1e-12);
  }
  const TriangleMesh outward = sphere.flipped();
  EXPECT_LT((outward.faceNormals()[0] + sphere.faceNormals()[0]).norm(), 1e-12);
}

TEST(TriangleMesh, EdgeFaceAdjacency)
{
  const TriangleMesh sphere = fixtures::makeSphere(1.0, 1);
  for (const MeshEdge& e : sphere.edges())
  {
    ASSERT_FALSE(e.isBoundary());
    ASSERT_LT(e.vertex0, e.vertex1);
    for (int face : { e.face0, e.face1 })
    {
      const Eigen::Vector3i& tri = sphere.faces()[face];
      EXPECT_TRUE((tri.array() == e.vertex0).any());
      EXPECT_TRUE((tri.array() == e.vertex1).any());
    }
    EXPECT_NE(e.face0, e.face1);
  }
  // Euler: V - E + F = 2 for a sphere.
  EXPECT_EQ(
    sphere.numberOfVertices() - static_cast<int>(sphere.edges().size()) + sphere.numberOfFaces(),
    2);
}

TEST(TriangleMesh, OpenAndNonManifoldEdgesAreCounted)
{
  // Three triangles sharing the edge (0, 1): non-manifold; all other edges open.
  const TriangleMesh fan({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 0, -1, 0 } },
    { { 0, 1, 2 }, { 0, 1, 3 }, { 1, 0, 4 } });
  EXPECT_EQ(fan.numberOfNonManifoldEdges(), 1);
  EXPECT_EQ(fan.numberOfBoundaryEdges(), 6);
}

TEST(TriangleMesh, ZeroAreaFacesKeepAZeroNormal)
{
  const TriangleMesh sliver({ { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 } }, { { 0, 1, 2 } });
  EXPECT_EQ(sliver.faceAreas()[0], 0.0);
  EXPECT_EQ(sliver.faceNormals()[0], Eigen::Vector3d::Zero());
}

TEST(TriangleMesh, RejectsBadInputWithAMessage)
{
  try
  {
    TriangleMesh({ { 0, 0, 0 }, { 1, 0, 0 } }, { { 0, 1, 2 } });
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "mesh face 0 refers to vertex 2 but the mesh has 2 vertices");
  }
  EXPECT_THROW(TriangleMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { { 0, 1, 1 } }), Error);
  EXPECT_THROW(
    TriangleMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, std::nan(""), 0 } }, { { 0, 1, 2 } }), Error);
  // A mesh without faces is a valid, empty value.
  EXPECT_EQ(TriangleMesh().numberOfFaces(), 0);
}
