#include <vimlop/Core/ClosestPointOnTriangle.h>

#include <Eigen/Dense>

#include <algorithm>
#include <limits>

namespace vimlop
{

namespace
{

/// Parameter in [0, 1] of the point of segment [a, b] closest to p.
double segmentParameter(
  const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  return length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
}

/// Barycentric weights of the closest point to p on the three edges.
Eigen::Vector3d closestOnEdges(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
  const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
  const double tab = segmentParameter(p, a, b);
  const double tac = segmentParameter(p, a, c);
  const double tbc = segmentParameter(p, b, c);
  const Eigen::Vector3d candidates[3] = { { 1.0 - tab, tab, 0.0 }, { 1.0 - tac, 0.0, tac },
    { 0.0, 1.0 - tbc, tbc } };
  Eigen::Vector3d best = candidates[0];
  double bestDistance2 = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& w : candidates)
  {
    const double d2 = (w[0] * a + w[1] * b + w[2] * c - p).squaredNorm();
    if (d2 < bestDistance2)
    {
      bestDistance2 = d2;
      best = w;
    }
  }
  return best;
}

} // namespace

Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
  const Eigen::Vector3d& b, const Eigen::Vector3d& c, Eigen::Vector3d* barycentric)
{
  // Region tests in the style of Ericson, "Real-Time Collision Detection", 5.1.5.
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  const Eigen::Vector3d ap = p - a;
  Eigen::Vector3d w;
  if (!(ab.cross(ac).squaredNorm() > 1e-24 * ab.squaredNorm() * ac.squaredNorm()))
  {
    // Degenerate (collinear or coincident corners): the answer lies on an edge,
    // and the region tests below would divide by zero.
    w = closestOnEdges(p, a, b, c);
    if (barycentric)
    {
      *barycentric = w;
    }
    return w[0] * a + w[1] * b + w[2] * c;
  }
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0)
  {
    w << 1.0, 0.0, 0.0;
  }
  else
  {
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp);
    const double d4 = ac.dot(bp);
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp);
    const double d6 = ac.dot(cp);
    const double vc = d1 * d4 - d3 * d2;
    const double vb = d5 * d2 - d1 * d6;
    const double va = d3 * d6 - d5 * d4;
    if (d3 >= 0.0 && d4 <= d3)
    {
      w << 0.0, 1.0, 0.0;
    }
    else if (d6 >= 0.0 && d5 <= d6)
    {
      w << 0.0, 0.0, 1.0;
    }
    else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
    {
      const double t = d1 / (d1 - d3);
      w << 1.0 - t, t, 0.0;
    }
    else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
    {
      const double t = d2 / (d2 - d6);
      w << 1.0 - t, 0.0, t;
    }
    else if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    {
      const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      w << 0.0, 1.0 - t, t;
    }
    else
    {
      const double denom = va + vb + vc;
      w << va / denom, vb / denom, vc / denom;
    }
  }
  if (barycentric)
  {
    *barycentric = w;
  }
  return w[0] * a + w[1] * b + w[2] * c;
}

} // namespace vimlop
