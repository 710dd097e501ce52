#include <vimlop/Core/MeshTree.h>

#include <vimlop/Core/ClosestPointOnTriangle.h>
#include <vimlop/Core/Error.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace vimlop
{

namespace
{

thread_local long long visitedFaces = 0;

double boxDistance2(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
{
  const Eigen::Vector3d d = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
  return d.squaredNorm();
}

/// Whitening of a covariance M = L Lᵀ: W = L⁻¹, so that dᵀ M⁻¹ d = |W d|².
struct Whitening
{
  Eigen::Matrix3d W;
  double lambdaMax;
  /// Separating axes of the cost ellipsoid ½ dᵀ M⁻¹ d <= B: the coordinate
  /// axes and M's eigenvectors (columns), and 2 aᵀ M a for each, since the
  /// ellipsoid reaches sqrt(2 B aᵀ M a) from its centre along a unit axis a.
  Eigen::Matrix<double, 3, 6> axes;
  Eigen::Matrix<double, 3, 6> absoluteAxes;
  Eigen::Matrix<double, 6, 1> twiceVariance;

  explicit Whitening(const Eigen::Matrix3d& covariance)
  {
    const Eigen::LLT<Eigen::Matrix3d> llt(covariance);
    if (llt.info() != Eigen::Success)
    {
      throw Error("most likely point: the covariance is not positive definite");
    }
    W = llt.matrixL().solve(Eigen::Matrix3d::Identity());
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(covariance);
    lambdaMax = eigen.eigenvalues()[2];
    axes << Eigen::Matrix3d::Identity(), eigen.eigenvectors();
    absoluteAxes = axes.cwiseAbs();
    twiceVariance.head<3>() = 2.0 * covariance.diagonal();
    twiceVariance.tail<3>() = 2.0 * eigen.eigenvalues();
  }

  /// True when no point of the box [lo, hi] can cost at most `bestCost`: on
  /// one of the axes, the box's projection misses the cost ellipsoid's. With
  /// the elongated covariances of V2 (view-aligned SfM noise) this prunes far
  /// more than the sphere of radius sqrt(2 B λmax), and like it never drops
  /// a better point, so the answer is unchanged.
  bool missesEllipsoid(const Eigen::Vector3d& z, const Eigen::Vector3d& lo,
    const Eigen::Vector3d& hi, double bestCost) const
  {
    const Eigen::Vector3d centre = 0.5 * (lo + hi) - z;
    const Eigen::Vector3d half = 0.5 * (hi - lo);
    const Eigen::Array<double, 6, 1> gap =
      ((axes.transpose() * centre).cwiseAbs() - absoluteAxes.transpose() * half).array().max(0.0);
    return (gap.square() > bestCost * twiceVariance.array()).any();
  }
};

/// Cost ½|W(y - z)|² of the whitened closest point on one face; fills `best` if lower.
inline void evaluateFace(const TriangleMesh& mesh, int face, const Eigen::Vector3d& z,
  const Whitening& w, MostLikelyPoint& best)
{
  const Eigen::Vector3d a = w.W * (mesh.corner(face, 0) - z);
  const Eigen::Vector3d b = w.W * (mesh.corner(face, 1) - z);
  const Eigen::Vector3d c = w.W * (mesh.corner(face, 2) - z);
  Eigen::Vector3d weights;
  const Eigen::Vector3d q = closestPointOnTriangle(Eigen::Vector3d::Zero(), a, b, c, &weights);
  const double cost = 0.5 * q.squaredNorm();
  if (cost < best.cost)
  {
    best.cost = cost;
    best.surfacePoint.face = face;
    best.surfacePoint.barycentric = weights;
  }
}

void finish(const TriangleMesh& mesh, const Eigen::Vector3d& z, MostLikelyPoint& best)
{
  SurfacePoint& p = best.surfacePoint;
  if (p.face < 0)
  {
    return;
  }
  p.point = p.barycentric[0] * mesh.corner(p.face, 0) + p.barycentric[1] * mesh.corner(p.face, 1) +
    p.barycentric[2] * mesh.corner(p.face, 2);
  p.distanceMm = (p.point - z).norm();
}

/// What MeshTree::traverse does at the tree's nodes: `skipBox(lo, hi)` may
/// reject a node on a bound of the search's own, `operator()(face)`
/// evaluates a face of a leaf that was not rejected.
template <typename Evaluate, typename SkipBox>
struct LeafVisitor
{
  Evaluate evaluate;
  SkipBox skip;
  void operator()(int face) { this->evaluate(face); }
  bool skipBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const
  {
    return this->skip(lo, hi);
  }
};

template <typename Evaluate, typename SkipBox>
LeafVisitor<Evaluate, SkipBox> makeLeafVisitor(Evaluate evaluate, SkipBox skip)
{
  return { std::move(evaluate), std::move(skip) };
}

} // namespace

MeshTree::MeshTree(const TriangleMesh& mesh, int leafSize)
  : Mesh(mesh)
  , LeafSize(std::max(1, leafSize))
{
  const int n = mesh.numberOfFaces();
  if (n == 0)
  {
    throw Error("cannot build a search tree: the mesh has no faces");
  }
  std::vector<Eigen::Vector3d> centroids(n);
  this->Faces.resize(n);
  for (int f = 0; f < n; ++f)
  {
    centroids[f] = mesh.faceCentroid(f);
    this->Faces[f] = f;
  }
  this->Nodes.reserve(static_cast<size_t>(4 * n / this->LeafSize + 1));
  this->build(0, n, centroids);
}

int MeshTree::build(int begin, int end, std::vector<Eigen::Vector3d>& centroids)
{
  const int index = static_cast<int>(this->Nodes.size());
  this->Nodes.emplace_back();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  Eigen::Vector3d clo = lo;
  Eigen::Vector3d chi = hi;
  for (int i = begin; i < end; ++i)
  {
    const int f = this->Faces[i];
    for (int k = 0; k < 3; ++k)
    {
      lo = lo.cwiseMin(this->Mesh.corner(f, k));
      hi = hi.cwiseMax(this->Mesh.corner(f, k));
    }
    clo = clo.cwiseMin(centroids[f]);
    chi = chi.cwiseMax(centroids[f]);
  }
  this->Nodes[index].lo = lo;
  this->Nodes[index].hi = hi;
  if (end - begin <= this->LeafSize)
  {
    this->Nodes[index].first = begin;
    this->Nodes[index].count = end - begin;
    return index;
  }
  // Median split of the centroids along the longest axis of their bounds.
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(this->Faces.begin() + begin, this->Faces.begin() + mid,
    this->Faces.begin() + end,
    [&](int a, int b) { return centroids[a][axis] < centroids[b][axis]; });
  this->build(begin, mid, centroids);
  const int right = this->build(mid, end, centroids);
  this->Nodes[index].right = right;
  return index;
}

// `visit` is a leaf visitor: visit(face) evaluates one face, and
// visit.skipBox(lo, hi) may reject a node on a bound of its own besides the
// distance bound.
template <typename LeafVisitor>
void MeshTree::traverse(const Eigen::Vector3d& z, double& pruneDistance2, LeafVisitor&& visit) const
{
  // Depth-first, nearer child first, with an explicit stack of (node, distance²).
  std::pair<int, double> stack[128];
  int top = 0;
  stack[top++] = { 0, boxDistance2(z, this->Nodes[0].lo, this->Nodes[0].hi) };
  while (top > 0)
  {
    const auto [index, d2] = stack[--top];
    const Node& node = this->Nodes[index];
    if (d2 > pruneDistance2 || visit.skipBox(node.lo, node.hi))
    {
      continue;
    }
    if (node.count > 0)
    {
      for (int i = node.first; i < node.first + node.count; ++i)
      {
        visit(this->Faces[i]);
      }
      continue;
    }
    const int left = index + 1;
    const int right = node.right;
    const double dl = boxDistance2(z, this->Nodes[left].lo, this->Nodes[left].hi);
    const double dr = boxDistance2(z, this->Nodes[right].lo, this->Nodes[right].hi);
    // Push the farther child first so the nearer one is explored first.
    if (dl <= dr)
    {
      stack[top++] = { right, dr };
      stack[top++] = { left, dl };
    }
    else
    {
      stack[top++] = { left, dl };
      stack[top++] = { right, dr };
    }
  }
}

SurfacePoint MeshTree::closestPoint(const Eigen::Vector3d& query) const
{
  MostLikelyPoint best;
  best.cost = std::numeric_limits<double>::infinity();
  double prune2 = std::numeric_limits<double>::infinity();
  long long visited = 0;
  this->traverse(query, prune2,
    makeLeafVisitor(
      [&](int face)
      {
        ++visited;
        Eigen::Vector3d weights;
        const Eigen::Vector3d q = closestPointOnTriangle(query, this->Mesh.corner(face, 0),
          this->Mesh.corner(face, 1), this->Mesh.corner(face, 2), &weights);
        const double d2 = (q - query).squaredNorm();
        if (d2 < prune2)
        {
          prune2 = d2;
          best.surfacePoint.face = face;
          best.surfacePoint.barycentric = weights;
        }
      },
      [](const Eigen::Vector3d&, const Eigen::Vector3d&) { return false; }));
  visitedFaces += visited;
  finish(this->Mesh, query, best);
  return best.surfacePoint;
}

MostLikelyPoint MeshTree::mostLikelyPoint(
  const Eigen::Vector3d& z, const Eigen::Matrix3d& covariance, int hintFace) const
{
  const Whitening w(covariance);
  MostLikelyPoint best;
  best.cost = std::numeric_limits<double>::infinity();
  long long visited = 0;
  if (hintFace >= 0 && hintFace < this->Mesh.numberOfFaces())
  {
    evaluateFace(this->Mesh, hintFace, z, w, best);
    ++visited;
  }
  double prune2 = 2.0 * best.cost * w.lambdaMax;
  this->traverse(z, prune2,
    makeLeafVisitor(
      [&](int face)
      {
        // A leaf's faces are tested one by one against the same bound as
        // the nodes, which is much cheaper than their closest point.
        const Eigen::Vector3d a = this->Mesh.corner(face, 0);
        const Eigen::Vector3d b = this->Mesh.corner(face, 1);
        const Eigen::Vector3d c = this->Mesh.corner(face, 2);
        if (w.missesEllipsoid(z, a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), best.cost))
        {
          return;
        }
        ++visited;
        evaluateFace(this->Mesh, face, z, w, best);
        prune2 = 2.0 * best.cost * w.lambdaMax;
      },
      [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
      { return w.missesEllipsoid(z, lo, hi, best.cost); }));
  visitedFaces += visited;
  finish(this->Mesh, z, best);
  return best;
}

bool MeshTree::isSegmentOccluded(
  const Eigen::Vector3d& from, const Eigen::Vector3d& to, double toleranceMm) const
{
  const Eigen::Vector3d d = to - from;
  const double length = d.norm();
  if (!(length > 2.0 * toleranceMm))
  {
    return false;
  }
  const Eigen::Vector3d dir = d / length;
  const Eigen::Vector3d inv = dir.cwiseInverse(); // infinities are fine for the slab test
  const double tMin = toleranceMm;
  const double tMax = length - toleranceMm;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const int index = stack[--top];
    const Node& node = this->Nodes[index];
    // Slab test of the segment [tMin, tMax] against the node's box.
    const Eigen::Vector3d t0 = (node.lo - from).cwiseProduct(inv);
    const Eigen::Vector3d t1 = (node.hi - from).cwiseProduct(inv);
    const double enter = std::max(tMin, t0.cwiseMin(t1).maxCoeff());
    const double leave = std::min(tMax, t0.cwiseMax(t1).minCoeff());
    if (!(enter <= leave))
    {
      continue;
    }
    if (node.count == 0)
    {
      stack[top++] = node.right;
      stack[top++] = index + 1;
      continue;
    }
    for (int i = node.first; i < node.first + node.count; ++i)
    {
      // Moller-Trumbore, double precision.
      const int f = this->Faces[i];
      const Eigen::Vector3d& a = this->Mesh.corner(f, 0);
      const Eigen::Vector3d e1 = this->Mesh.corner(f, 1) - a;
      const Eigen::Vector3d e2 = this->Mesh.corner(f, 2) - a;
      const Eigen::Vector3d p = dir.cross(e2);
      const double det = e1.dot(p);
      if (std::abs(det) < 1e-300)
      {
        continue;
      }
      const Eigen::Vector3d s = from - a;
      const double u = s.dot(p) / det;
      if (u < 0.0 || u > 1.0)
      {
        continue;
      }
      const Eigen::Vector3d q = s.cross(e1);
      const double v = dir.dot(q) / det;
      if (v < 0.0 || u + v > 1.0)
      {
        continue;
      }
      const double t = e2.dot(q) / det;
      if (t > tMin && t < tMax)
      {
        return true;
      }
    }
  }
  return false;
}

MostLikelyPoint MeshTree::mostLikelyPointBruteForce(
  const TriangleMesh& mesh, const Eigen::Vector3d& z, const Eigen::Matrix3d& covariance)
{
  const Whitening w(covariance);
  MostLikelyPoint best;
  best.cost = std::numeric_limits<double>::infinity();
  for (int f = 0; f < mesh.numberOfFaces(); ++f)
  {
    evaluateFace(mesh, f, z, w, best);
  }
  visitedFaces += mesh.numberOfFaces();
  finish(mesh, z, best);
  return best;
}

long long MeshTree::facesVisited()
{
  return visitedFaces;
}

} // namespace vimlop
