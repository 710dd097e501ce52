#include <vimlop/Evaluation/MucosalSwelling.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/MeshTree.h>
#include <vimlop/Core/RayClearance.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/NasalCavityRegion.h>

#include <algorithm>
#include <cmath>

namespace vimlop
{

namespace
{

double smoothStep(double edge0, double edge1, double x)
{
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// 1 deeper than `edgeMm` inside [low, high], falling as a raised cosine to 0 at its ends.
double insideWeight(double x, double low, double high, double edgeMm)
{
  const double depth = std::min(x - low, high - x);
  if (depth <= 0.0)
  {
    return 0.0;
  }
  if (edgeMm <= 0.0 || depth >= edgeMm)
  {
    return 1.0;
  }
  return 0.5 - 0.5 * std::cos(M_PI * depth / edgeMm);
}

} // namespace

void MucosalSwellingOptions::validate() const
{
  if (!(this->swellingMm >= 0.0 && this->swellingMm <= 5.0))
  {
    throw Error(
      "the mucosal swelling must lie in [0, 5] mm, not " + formatText("%g", this->swellingMm));
  }
  for (double f : { this->anteriorFraction, this->lowFraction, this->highFraction })
  {
    if (!(f >= 0.0 && f <= 1.0))
    {
      throw Error("the swelling region's fractions must lie in [0, 1], not " + formatText("%g", f));
    }
  }
  if (!(this->lowFraction < this->highFraction))
  {
    throw Error("the swelling region's low fraction must be below its high fraction");
  }
  if (!(this->maxFreeFraction > 0.0 && this->maxFreeFraction < 0.5))
  {
    throw Error("the swelling's share of the free length must lie in (0, 0.5), not " +
      formatText("%g", this->maxFreeFraction));
  }
  if (!(this->edgeMm >= 0.0) || this->smoothingIterations < 0)
  {
    throw Error("the swelling region's edge and smoothing must not be negative");
  }
}

SwollenSurface swellMucosa(const TriangleMesh& airway, const MucosalSwellingOptions& o)
{
  o.validate();
  const std::vector<Eigen::Vector3d>& vertices = airway.vertices();
  const std::size_t n = vertices.size();
  SwollenSurface out;
  out.displacementMm.assign(n, 0.0);
  if (o.isOff() || n == 0)
  {
    out.mesh = airway;
    return out;
  }
  const NasalCavityRegion nose =
    NasalCavityRegion::inBounds(airway.bounds(), o.anteriorFraction, o.lowFraction, o.highFraction);

  // Weighted normal displacements, then smoothed over the mesh: the normals
  // of a segmented surface turn from vertex to vertex, and unsmoothed
  // displacements would roughen the wall.
  const std::vector<Eigen::Vector3d>& normals = airway.vertexNormals();
  std::vector<Eigen::Vector3d> d(n, Eigen::Vector3d::Zero());
  int inRegion = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Eigen::Vector3d& v = vertices[i];
    const double w = insideWeight(v.y(), nose.yFrontMm - o.edgeMm, nose.yBackMm, o.edgeMm) *
      insideWeight(v.z(), nose.zLowMm, nose.zHighMm, o.edgeMm) *
      smoothStep(0.4, 0.7, std::abs(normals[i].x()));
    inRegion += w > 0.0 ? 1 : 0;
    d[i] = w * normals[i];
  }
  if (inRegion == 0)
  {
    throw Error("mucosal swelling: no vertex of the airway lies in the nasal cavity's region "
                "(is the mesh a nasal airway in the CT frame, LPS?)");
  }
  std::vector<std::vector<int>> neighbours(n);
  for (const MeshEdge& e : airway.edges())
  {
    neighbours[e.vertex0].push_back(e.vertex1);
    neighbours[e.vertex1].push_back(e.vertex0);
  }
  for (int round = 0; round < o.smoothingIterations; ++round)
  {
    std::vector<Eigen::Vector3d> next(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      Eigen::Vector3d sum = d[i];
      for (int j : neighbours[i])
      {
        sum += d[j];
      }
      next[i] = sum / static_cast<double>(neighbours[i].size() + 1);
    }
    d.swap(next);
  }
  double largest = 0.0;
  for (const Eigen::Vector3d& di : d)
  {
    largest = std::max(largest, di.norm());
  }
  std::vector<Eigen::Vector3d> moved = vertices;
  const double scale = o.swellingMm / largest;
  // Swollen mucosa closes a passage but never passes through the opposite
  // wall: each vertex moves at most `maxFreeFraction` of the free length
  // ahead of it (walked in 0.1 mm steps from just off the wall).
  const MeshTree tree(airway);
  constexpr double offMm = 0.05;
  for (std::size_t i = 0; i < n; ++i)
  {
    double length = scale * d[i].norm();
    if (length > 0.0)
    {
      const Eigen::Vector3d direction = d[i].normalized();
      const double free = offMm +
        freeLengthAlongRay(
          tree, vertices[i] + offMm * direction, direction, length / o.maxFreeFraction, 0.1);
      length = std::min(length, o.maxFreeFraction * free);
      moved[i] += length * direction;
    }
    out.displacementMm[i] = length;
  }
  out.mesh = TriangleMesh(std::move(moved), airway.faces());
  const double threshold = 0.1 * o.swellingMm;
  for (int f = 0; f < airway.numberOfFaces(); ++f)
  {
    const Eigen::Vector3i& face = airway.faces()[f];
    if (out.displacementMm[face[0]] > threshold && out.displacementMm[face[1]] > threshold &&
      out.displacementMm[face[2]] > threshold)
    {
      out.swollenAreaMm2 += airway.faceAreas()[f];
    }
  }
  return out;
}

} // namespace vimlop
