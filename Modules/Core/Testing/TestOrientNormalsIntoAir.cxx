#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/OrientNormalsIntoAir.h>

#include <gtest/gtest.h>

using namespace vimlop;

TEST(OrientNormalsIntoAir, ACavityWithNormalsIntoTheAirIsKept)
{
  const TriangleMesh cavity = fixtures::makeSphere(10.0, 2);
  std::string note = "stale";
  const TriangleMesh oriented = orientNormalsIntoAir(cavity, &note);
  EXPECT_EQ(oriented.faces(), cavity.faces());
  EXPECT_EQ(note, "");
}

TEST(OrientNormalsIntoAir, AClosedSurfaceWithNormalsOutOfItsAirIsFlipped)
{
  const TriangleMesh outward = fixtures::makeSphere(10.0, 2, Eigen::Vector3d::Zero(), true);
  ASSERT_GT(outward.signedVolume(), 0.0);
  std::string note;
  const TriangleMesh oriented = orientNormalsIntoAir(outward, &note);
  EXPECT_NEAR(oriented.signedVolume(), -outward.signedVolume(), 1e-9 * outward.signedVolume());
  EXPECT_LT(oriented.faceNormals()[0].dot(outward.faceNormals()[0]), -0.999);
  EXPECT_EQ(note, "the surface's normals point out of the air it encloses; flipped them");
  EXPECT_NO_THROW(orientNormalsIntoAir(outward));
}

TEST(OrientNormalsIntoAir, AnOpenSurfaceKeepsItsFaceOrderWithANote)
{
  const TriangleMesh box = fixtures::makeBox({ -1, -1, -1 }, { 1, 1, 1 }, true);
  std::vector<Eigen::Vector3i> faces = box.faces();
  faces.erase(faces.begin(), faces.begin() + 2); // one side open
  const TriangleMesh open(box.vertices(), faces);
  ASSERT_GT(open.numberOfBoundaryEdges(), 0);
  std::string note;
  const TriangleMesh oriented = orientNormalsIntoAir(open, &note);
  EXPECT_EQ(oriented.faces(), open.faces());
  EXPECT_EQ(note,
    "the surface is open, so the side of the air cannot be told from it; kept its face order "
    "(its normals must point into the air)");
}

TEST(OrientNormalsIntoAir, AMeshWithoutFacesGetsAClearError)
{
  try
  {
    orientNormalsIntoAir(TriangleMesh());
    ADD_FAILURE() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_EQ(std::string(e.what()), "orient normals into the air: the mesh has no faces");
  }
}
