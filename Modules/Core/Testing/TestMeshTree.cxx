#include "RandomGeometry.h"
#include "TestMeshes.h"
#include <vimlop/Core/ClosestPointOnTriangle.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/MeshTree.h>

#include <gtest/gtest.h>

using namespace vimlop;

TEST(MeshTree, MostLikelyPointMatchesBruteForce)
{
  for (unsigned seed : { 1u, 2u, 3u })
  {
    const TriangleMesh mesh = fixtures::makeRandomSoup(500, seed);
    const MeshTree tree(mesh);
    std::mt19937 rng(seed + 10);
    std::uniform_real_distribution<double> u(-25.0, 25.0);
    for (int i = 0; i < 200; ++i)
    {
      const Eigen::Vector3d z(u(rng), u(rng), u(rng));
      // Anisotropy up to 20:1, as view-aligned SfM noise can be.
      const Eigen::Matrix3d cov = fixtures::randomCovariance(rng, 0.1, 2.0);
      const MostLikelyPoint fast = tree.mostLikelyPoint(z, cov, i % 3 == 0 ? i : -1);
      const MostLikelyPoint reference = MeshTree::mostLikelyPointBruteForce(mesh, z, cov);
      ASSERT_NEAR(fast.cost, reference.cost, 1e-9 * (1.0 + reference.cost));
      // The cost is what it claims: ½ dᵀ M⁻¹ d.
      const Eigen::Vector3d d = fast.surfacePoint.point - z;
      EXPECT_NEAR(0.5 * d.dot(cov.inverse() * d), fast.cost, 1e-9 * (1.0 + fast.cost));
    }
  }
}

TEST(MeshTree, MostLikelyPointPrefersTheLikelyDirection)
{
  // Two walls: z = 0, 1 mm from the query along z, and x = 3, 3 mm along x.
  // With noise long along x and tight along z, the wall 3 mm away along x
  // is more likely than the wall 1 mm away along z.
  const TriangleMesh walls({ { -50, -50, 0 }, { 50, -50, 0 }, { 0, 50, 0 }, { 3, -50, -50 },
                             { 3, 50, -50 }, { 3, 0, 50 } },
    { { 0, 1, 2 }, { 3, 4, 5 } });
  const MeshTree tree(walls);
  Eigen::Matrix3d cov = Eigen::Vector3d(9.0, 1.0, 0.01).asDiagonal();
  const Eigen::Vector3d z(0.0, 0.0, 1.0);
  EXPECT_EQ(tree.mostLikelyPoint(z, cov).surfacePoint.face, 1);
  EXPECT_EQ(tree.closestPoint(z).face, 0);
  cov = Eigen::Vector3d(0.01, 1.0, 9.0).asDiagonal();
  EXPECT_EQ(tree.mostLikelyPoint(z, cov).surfacePoint.face, 0);
}

TEST(MeshTree, TreeVisitsFewFaces)
{
  const TriangleMesh sphere = fixtures::makeSphere(20.0, 5); // 20480 faces
  const MeshTree tree(sphere);
  std::mt19937 rng(4);
  const long long before = MeshTree::facesVisited();
  for (int i = 0; i < 100; ++i)
  {
    const Eigen::Vector3d z = 19.0 * fixtures::randomUnit(rng);
    tree.mostLikelyPoint(z, fixtures::randomCovariance(rng, 0.3, 0.5));
  }
  // The eigenvalue bound prunes all but a small neighbourhood.
  EXPECT_LT((MeshTree::facesVisited() - before) / 100, sphere.numberOfFaces() / 20);
}

TEST(MeshTree, NoiseLongAlongTheViewVisitsOnlyTheFacesAlongTheView)
{
  // SfM points are uncertain along their camera ray (V2's view-aligned noise),
  // and the ray meets the wall head on: the likely region is a thin needle
  // across the wall. The cost ellipsoid's bounding box keeps only the faces
  // near the needle, where the sphere of radius sqrt(2 B λmax) would keep a
  // disc of the wall 1 mm across. Faces are tested one by one against the
  // same axes before their closest point is sought.
  const TriangleMesh sphere = fixtures::makeSphere(20.0, 5); // 20480 faces, 0.25 mm² each
  const MeshTree tree(sphere);
  const long long before = MeshTree::facesVisited();
  int queries = 0;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (double side : { -1.0, 1.0 })
    {
      // Along an axis, so that the needle's bounding box is thin too.
      const Eigen::Vector3d along = Eigen::Vector3d::Unit(axis);
      const Eigen::Vector3d z = 19.0 * side * along;
      const Eigen::Matrix3d cov = 4.0 * along * along.transpose() +
        0.01 * (Eigen::Matrix3d::Identity() - along * along.transpose());
      const MostLikelyPoint fast = tree.mostLikelyPoint(z, cov);
      const MostLikelyPoint reference = MeshTree::mostLikelyPointBruteForce(sphere, z, cov);
      ASSERT_NEAR(fast.cost, reference.cost, 1e-9 * (1.0 + reference.cost));
      ++queries;
    }
  }
  const double perQuery = static_cast<double>(MeshTree::facesVisited() - before -
                            queries * static_cast<long long>(sphere.numberOfFaces())) /
    queries;
  // The sphere bound alone evaluates 26 faces per query here, the ellipsoid's
  // axes 8.
  EXPECT_LT(perQuery, 12.0);
}

TEST(MeshTree, ClosestPointMatchesBruteForce)
{
  const TriangleMesh mesh = fixtures::makeRandomSoup(300, 9);
  const MeshTree tree(mesh);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  for (int i = 0; i < 200; ++i)
  {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    double best = std::numeric_limits<double>::infinity();
    for (int f = 0; f < mesh.numberOfFaces(); ++f)
    {
      best = std::min(best,
        (closestPointOnTriangle(p, mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2)) - p)
          .norm());
    }
    EXPECT_NEAR(tree.closestPoint(p).distanceMm, best, 1e-9);
  }
}

TEST(MeshTree, SegmentOcclusion)
{
  const TriangleMesh sphere = fixtures::makeSphere(10.0, 3);
  const MeshTree tree(sphere);
  std::mt19937 rng(5);
  for (int i = 0; i < 100; ++i)
  {
    const Eigen::Vector3d onSurface = sphere.faceCentroid(i * 7 % sphere.numberOfFaces());
    // From inside the cavity every wall point is visible...
    EXPECT_FALSE(tree.isSegmentOccluded(0.3 * fixtures::randomUnit(rng), onSurface));
    // ... from outside, the far side is hidden by the near side.
    EXPECT_TRUE(tree.isSegmentOccluded(-3.0 * onSurface, onSurface));
  }
}

TEST(MeshTree, RejectsBadInput)
{
  EXPECT_THROW(MeshTree{ TriangleMesh() }, Error);
  const MeshTree tree(fixtures::makeSphere(1.0, 1));
  Eigen::Matrix3d singular = Eigen::Matrix3d::Identity();
  singular(2, 2) = -1.0;
  try
  {
    tree.mostLikelyPoint(Eigen::Vector3d::Zero(), singular);
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "most likely point: the covariance is not positive definite");
  }
}
