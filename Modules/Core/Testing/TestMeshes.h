#ifndef vimlop_TestMeshes_h
#define vimlop_TestMeshes_h

// Meshes that tests build in memory, with known geometry.

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/TriangleMesh.h>

#include <Eigen/Core>

#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace vimlop::fixtures
{

/// Icosphere of `radius` (mm) centred at `centre`; normals inward (into the
/// cavity, VIMLOP's convention for an airway) unless `outward`.
inline TriangleMesh makeSphere(double radius, int subdivisions,
  const Eigen::Vector3d& centre = Eigen::Vector3d::Zero(), bool outward = false)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 },
    { 0, -1, t }, { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 },
    { -t, 0, -1 }, { -t, 0, 1 } };
  std::vector<Eigen::Vector3i> f = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 },
    { 0, 10, 11 }, { 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 }, { 3, 9, 4 },
    { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 },
    { 8, 6, 7 }, { 9, 8, 1 } };
  for (Eigen::Vector3d& p : v)
  {
    p.normalize();
  }
  for (int s = 0; s < subdivisions; ++s)
  {
    std::map<std::pair<int, int>, int> midpoints;
    auto midpoint = [&](int a, int b)
    {
      const std::pair<int, int> key(std::min(a, b), std::max(a, b));
      auto it = midpoints.find(key);
      if (it != midpoints.end())
      {
        return it->second;
      }
      v.push_back((v[a] + v[b]).normalized());
      midpoints[key] = static_cast<int>(v.size()) - 1;
      return static_cast<int>(v.size()) - 1;
    };
    std::vector<Eigen::Vector3i> refined;
    for (const Eigen::Vector3i& tri : f)
    {
      const int ab = midpoint(tri[0], tri[1]);
      const int bc = midpoint(tri[1], tri[2]);
      const int ca = midpoint(tri[2], tri[0]);
      refined.push_back({ tri[0], ab, ca });
      refined.push_back({ tri[1], bc, ab });
      refined.push_back({ tri[2], ca, bc });
      refined.push_back({ ab, bc, ca });
    }
    f = std::move(refined);
  }
  for (Eigen::Vector3d& p : v)
  {
    p = centre + radius * p;
  }
  if (!outward)
  {
    for (Eigen::Vector3i& tri : f)
    {
      std::swap(tri[1], tri[2]);
    }
  }
  return TriangleMesh(std::move(v), std::move(f));
}

/// A closed cavity with folds: an icosphere of `radius` whose radius varies by
/// ±`amplitude` (a fraction) with direction, normals into the cavity. Seen from
/// inside, its bumps make occluding contours.
inline TriangleMesh makeBumpyCavity(
  double radius = 20.0, double amplitude = 0.25, int subdivisions = 4)
{
  const TriangleMesh sphere = makeSphere(1.0, subdivisions);
  std::vector<Eigen::Vector3d> v = sphere.vertices();
  for (Eigen::Vector3d& p : v)
  {
    const double bump =
      std::sin(3.0 * p.x() + 1.0) * std::sin(2.0 * p.y() - 0.5) * std::cos(2.5 * p.z()) +
      0.5 * std::sin(5.0 * p.z() + 2.0 * p.x());
    p *= radius * (1.0 + amplitude * bump);
  }
  return TriangleMesh(std::move(v), sphere.faces());
}

/// The union of several surfaces as one mesh (vertices renumbered).
inline TriangleMesh merge(const std::vector<TriangleMesh>& parts)
{
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  for (const TriangleMesh& part : parts)
  {
    const int offset = static_cast<int>(v.size());
    v.insert(v.end(), part.vertices().begin(), part.vertices().end());
    for (const Eigen::Vector3i& tri : part.faces())
    {
      f.push_back(tri + Eigen::Vector3i::Constant(offset));
    }
  }
  return TriangleMesh(std::move(v), std::move(f));
}

/// A blob in front of a larger blob, off its axis so that, seen by
/// twoBlobsCamera() from the origin along +z, it hides part of the larger
/// one's outline; both solid (normals out, into the air).
inline TriangleMesh twoBlobs()
{
  return merge(
    { makeSphere(3.0, 3, { 1.5, 0.0, 30.0 }, true), makeSphere(8.0, 3, { 0.0, 0.0, 60.0 }, true) });
}

/// The camera of twoBlobs(): the simulated endoscope's 320 x 240 px image
/// with a focal length of 300 px.
inline PinholeCamera twoBlobsCamera()
{
  PinholeCamera k = PinholeCamera::simulatedEndoscope();
  k.fx = k.fy = 300.0;
  return k;
}

/// An airway-like test model: a bumpy cavity of radius about 20 mm holding two
/// solid blobs (like turbinates), whose silhouettes make occluding contours
/// seen from inside. All normals point into the air.
inline TriangleMesh makeCavityWithBlobs()
{
  return merge({ makeBumpyCavity(20.0, 0.15, 4), makeSphere(4.0, 3, { 8.0, 0.0, 3.0 }, true),
    makeSphere(3.0, 3, { -6.0, 5.0, -4.0 }, true) });
}

/// A closed tube along +z from z = 0 to `length` (mm) around the z axis, like
/// a nasal passage: radius `radius` varied by the fraction `folds` with angle
/// and depth (so that folds make occluding contours seen from inside), capped
/// at both ends, normals into the air inside.
inline TriangleMesh makeTube(
  double radius = 4.0, double length = 60.0, double folds = 0.15, int sides = 48, int rings = 120)
{
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  for (int k = 0; k <= rings; ++k)
  {
    const double z = length * k / rings;
    for (int i = 0; i < sides; ++i)
    {
      const double theta = 2.0 * M_PI * i / sides;
      const double r = radius *
        (1.0 + folds * std::sin(3.0 * theta + 0.4 * z) * std::sin(0.5 * z) * std::sin(0.5 * z));
      v.emplace_back(r * std::cos(theta), r * std::sin(theta), z);
    }
  }
  auto index = [&](int i, int k) { return k * sides + (i % sides); };
  for (int k = 0; k < rings; ++k)
  {
    for (int i = 0; i < sides; ++i)
    {
      // (d/dtheta) x (d/dz) points out of the tube: reversed, into it.
      f.emplace_back(index(i, k), index(i, k + 1), index(i + 1, k));
      f.emplace_back(index(i + 1, k), index(i, k + 1), index(i + 1, k + 1));
    }
  }
  const int bottom = static_cast<int>(v.size());
  v.emplace_back(0.0, 0.0, 0.0);
  const int top = static_cast<int>(v.size());
  v.emplace_back(0.0, 0.0, length);
  for (int i = 0; i < sides; ++i)
  {
    f.emplace_back(bottom, index(i, 0), index(i + 1, 0));
    f.emplace_back(top, index(i + 1, rings), index(i, rings));
  }
  return TriangleMesh(std::move(v), std::move(f));
}

/// A camera on the axis of makeTube()'s tube, 10 mm in, looking down it (y up).
inline CameraPose cameraOnTheTubeAxis()
{
  return CameraPose::lookAt(
    Eigen::Vector3d(0.0, 0.0, 10.0), Eigen::Vector3d(0.0, 0.0, 30.0), Eigen::Vector3d::UnitY());
}

/// Axis-aligned box [lo, hi], two triangles per side; normals inward unless `outward`.
inline TriangleMesh makeBox(
  const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, bool outward = false)
{
  std::vector<Eigen::Vector3d> v;
  for (int i = 0; i < 8; ++i)
  {
    v.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  }
  // Outward-facing quads (counter-clockwise seen from outside).
  const int quads[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  std::vector<Eigen::Vector3i> f;
  for (const auto& q : quads)
  {
    f.push_back({ q[0], q[1], q[2] });
    f.push_back({ q[0], q[2], q[3] });
  }
  TriangleMesh mesh(std::move(v), std::move(f));
  return outward ? mesh : mesh.flipped();
}

/// A soup of `n` random triangles in [-size, size]^3 (edges up to `edge` mm).
inline TriangleMesh makeRandomSoup(int n, unsigned seed, double size = 20.0, double edge = 4.0)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> where(-size, size);
  std::uniform_real_distribution<double> offset(-edge, edge);
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  for (int i = 0; i < n; ++i)
  {
    const Eigen::Vector3d c(where(rng), where(rng), where(rng));
    for (int k = 0; k < 3; ++k)
    {
      v.push_back(c + Eigen::Vector3d(offset(rng), offset(rng), offset(rng)));
    }
    f.push_back({ 3 * i, 3 * i + 1, 3 * i + 2 });
  }
  return TriangleMesh(std::move(v), std::move(f));
}

} // namespace vimlop::fixtures

#endif
