#include "ErrorMessage.h"
#include "TestMeshes.h"
#include <vimlop/Core/ClosestPointOnTriangle.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Raycast/EmbreeScene.h>

#include <Eigen/Dense>

#include <gtest/gtest.h>

#include <limits>
#include <random>

using namespace vimlop;

namespace
{

double bruteForceDistance(const TriangleMesh& mesh, const Eigen::Vector3d& p)
{
  double best = std::numeric_limits<double>::infinity();
  for (int f = 0; f < mesh.numberOfFaces(); ++f)
  {
    best = std::min(best,
      (closestPointOnTriangle(p, mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2)) - p)
        .norm());
  }
  return best;
}

/// Segment-triangle test in double precision. Returns +1 for a clear crossing,
/// -1 for a clear miss and 0 when the segment passes within `margin` of a
/// triangle's border or ends, where single-precision traversal may go either way.
int bruteForceCrossing(const TriangleMesh& mesh, const Eigen::Vector3d& from,
  const Eigen::Vector3d& to, double tolerance, double margin)
{
  const Eigen::Vector3d d = to - from;
  const double length = d.norm();
  bool ambiguous = false;
  for (int f = 0; f < mesh.numberOfFaces(); ++f)
  {
    const Eigen::Vector3d a = mesh.corner(f, 0), b = mesh.corner(f, 1), c = mesh.corner(f, 2);
    const Eigen::Vector3d e1 = b - a, e2 = c - a;
    const Eigen::Vector3d p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-12)
    {
      continue;
    }
    const Eigen::Vector3d s = from - a;
    const double u = s.dot(p) / det;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = d.dot(q) / det;
    const double t = e2.dot(q) / det * length; // distance along the segment
    const double w = 1.0 - u - v;
    const double border = std::min({ u, v, w }); // in barycentric units
    const double scale = std::max(e1.norm(), e2.norm());
    const bool inside = border > margin / scale;
    const bool outside = border < -margin / scale;
    const bool within = t > tolerance + margin && t < length - tolerance - margin;
    const bool beyond = t < tolerance - margin || t > length - tolerance + margin;
    if (inside && within)
    {
      return 1;
    }
    if (!(outside || beyond))
    {
      ambiguous = true;
    }
  }
  return ambiguous ? 0 : -1;
}

} // namespace

TEST(EmbreeScene, ClosestPointMatchesBruteForceOnRandomMeshes)
{
  for (unsigned seed : { 1u, 2u, 3u })
  {
    const TriangleMesh mesh = fixtures::makeRandomSoup(400, seed);
    const EmbreeScene scene(mesh);
    std::mt19937 rng(seed + 100);
    std::uniform_real_distribution<double> u(-30.0, 30.0);
    for (int i = 0; i < 300; ++i)
    {
      const Eigen::Vector3d p(u(rng), u(rng), u(rng));
      const SurfacePoint hit = scene.closestPoint(p);
      ASSERT_TRUE(hit.isValid());
      EXPECT_NEAR(hit.distanceMm, bruteForceDistance(mesh, p), 1e-9);
      EXPECT_NEAR((hit.point - p).norm(), hit.distanceMm, 1e-12);
      // The reported face and weights reproduce the point.
      const Eigen::Vector3d rebuilt = hit.barycentric[0] * mesh.corner(hit.face, 0) +
        hit.barycentric[1] * mesh.corner(hit.face, 1) +
        hit.barycentric[2] * mesh.corner(hit.face, 2);
      EXPECT_LT((rebuilt - hit.point).norm(), 1e-9);
    }
  }
}

TEST(EmbreeScene, ClosestPointHonoursTheSearchRadius)
{
  const TriangleMesh sphere = fixtures::makeSphere(10.0, 3);
  const EmbreeScene scene(sphere);
  EXPECT_FALSE(scene.closestPoint(Eigen::Vector3d::Zero(), 5.0).isValid());
  const SurfacePoint hit = scene.closestPoint(Eigen::Vector3d::Zero(), 11.0);
  ASSERT_TRUE(hit.isValid());
  EXPECT_NEAR(hit.distanceMm, 10.0, 0.1);
}

TEST(EmbreeScene, SegmentOcclusionMatchesBruteForce)
{
  const TriangleMesh mesh = fixtures::makeRandomSoup(300, 7);
  const EmbreeScene scene(mesh);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-25.0, 25.0);
  int checked = 0;
  int occluded = 0;
  for (int i = 0; i < 2000; ++i)
  {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng));
    const Eigen::Vector3d b(u(rng), u(rng), u(rng));
    const int expected = bruteForceCrossing(mesh, a, b, 1e-3, 1e-3);
    if (expected == 0)
    {
      continue;
    }
    ++checked;
    occluded += expected > 0;
    EXPECT_EQ(scene.isSegmentOccluded(a, b), expected > 0) << "segment " << i;
  }
  // The set-up must exercise both answers.
  EXPECT_GT(checked, 1900);
  EXPECT_GT(occluded, 200);
  EXPECT_LT(occluded, checked - 200);
}

TEST(EmbreeScene, SegmentsEndingOnTheSurfaceAreVisibleFromInside)
{
  // From the centre of a cavity every surface point is visible; from outside
  // the far side is hidden by the near side.
  const TriangleMesh sphere = fixtures::makeSphere(10.0, 3);
  const EmbreeScene scene(sphere);
  for (int f = 0; f < sphere.numberOfFaces(); f += 7)
  {
    const Eigen::Vector3d onSurface = sphere.faceCentroid(f);
    EXPECT_FALSE(scene.isSegmentOccluded(Eigen::Vector3d::Zero(), onSurface));
    const Eigen::Vector3d outside = -2.0 * onSurface;
    EXPECT_TRUE(scene.isSegmentOccluded(outside, onSurface));
  }
}

TEST(EmbreeScene, CastRayFindsTheFirstHit)
{
  const TriangleMesh box = fixtures::makeBox({ -5, -5, -5 }, { 5, 5, 5 });
  const EmbreeScene scene(box);
  const auto hit = scene.castRay({ 1, 2, 0 }, Eigen::Vector3d::UnitX());
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distanceMm, 4.0, 1e-5);
  EXPECT_NEAR(hit->point.x(), 5.0, 1e-5);
  // The face hit is the +x wall, whose normal points back into the box.
  EXPECT_LT((box.faceNormals()[hit->face] + Eigen::Vector3d::UnitX()).norm(), 1e-12);
  EXPECT_FALSE(scene.castRay({ 1, 2, 0 }, Eigen::Vector3d::UnitX(), 3.0).has_value());
}

TEST(EmbreeScene, RefusesARayItCannotTraceWithAClearMessage)
{
  // Embree itself would abort on these.
  const EmbreeScene scene(fixtures::makeBox({ -5, -5, -5 }, { 5, 5, 5 }));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] {
                scene.castRay({ nan, 0, 0 }, Eigen::Vector3d::UnitX());
              }),
    "ray casting: a ray from (nan, 0, 0) along (1, 0, 0) up to inf mm cannot be traced");
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] {
                scene.castRay({ 0, 0, 0 }, Eigen::Vector3d::Zero(), 3.0);
              }),
    "ray casting: a ray from (0, 0, 0) along (0, 0, 0) up to 3 mm cannot be traced");
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] {
                scene.castRay({ 0, 0, 0 }, Eigen::Vector3d::UnitX(), -1.0);
              }),
    "ray casting: a ray from (0, 0, 0) along (1, 0, 0) up to -1 mm cannot be traced");
}

TEST(EmbreeScene, RejectsAnEmptyMesh)
{
  try
  {
    EmbreeScene scene{ TriangleMesh() };
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "cannot build a ray-casting scene: the mesh has no faces");
  }
}

TEST(EmbreeScene, RayStreamAgreesWithSingleQueries)
{
  const TriangleMesh mesh = fixtures::makeRandomSoup(300, 12);
  const EmbreeScene scene(mesh);
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-25.0, 25.0);
  const Eigen::Vector3d from(u(rng), u(rng), u(rng));
  std::vector<Eigen::Vector3d> to;
  std::vector<double> tolerances;
  for (int i = 0; i < 1000; ++i)
  {
    to.emplace_back(u(rng), u(rng), u(rng));
    tolerances.push_back(i % 10 == 0 ? 1e3 : 1e-3); // every tenth too short to test
  }
  std::vector<char> occluded;
  scene.areSegmentsOccluded(from, to, tolerances, occluded);
  ASSERT_EQ(occluded.size(), to.size());
  int hidden = 0;
  for (size_t i = 0; i < to.size(); ++i)
  {
    EXPECT_EQ(occluded[i] != 0, scene.isSegmentOccluded(from, to[i], tolerances[i])) << i;
    hidden += occluded[i];
  }
  EXPECT_GT(hidden, 50);
}
