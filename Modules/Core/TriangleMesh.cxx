#include <vimlop/Core/TriangleMesh.h>

#include <vimlop/Core/Error.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <utility>

namespace vimlop
{

TriangleMesh::TriangleMesh(
  std::vector<Eigen::Vector3d> vertices, std::vector<Eigen::Vector3i> faces)
  : Vertices(std::move(vertices))
  , Faces(std::move(faces))
{
  const int nv = this->numberOfVertices();
  for (int i = 0; i < nv; ++i)
  {
    if (!this->Vertices[i].allFinite())
    {
      std::ostringstream msg;
      msg << "mesh vertex " << i << " has non-finite coordinates";
      throw Error(msg.str());
    }
  }
  const int nf = this->numberOfFaces();
  this->FaceNormals.resize(nf);
  this->FaceAreas.resize(nf);
  for (int f = 0; f < nf; ++f)
  {
    const Eigen::Vector3i& tri = this->Faces[f];
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] < 0 || tri[k] >= nv)
      {
        std::ostringstream msg;
        msg << "mesh face " << f << " refers to vertex " << tri[k] << " but the mesh has " << nv
            << " vertices";
        throw Error(msg.str());
      }
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
    {
      std::ostringstream msg;
      msg << "mesh face " << f << " repeats a vertex (" << tri.transpose() << ")";
      throw Error(msg.str());
    }
    const Eigen::Vector3d n =
      (this->corner(f, 1) - this->corner(f, 0)).cross(this->corner(f, 2) - this->corner(f, 0));
    const double twiceArea = n.norm();
    this->FaceAreas[f] = 0.5 * twiceArea;
    this->FaceNormals[f] =
      twiceArea > 0.0 ? Eigen::Vector3d(n / twiceArea) : Eigen::Vector3d::Zero();
  }

  // Edge-face adjacency by sorting (edge key, face corner) pairs: O(F log F),
  // no hashing. Corner k of face f starts the edge from corner k to k + 1.
  std::vector<std::pair<std::uint64_t, int>> halfEdges;
  halfEdges.reserve(3 * static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint64_t a = static_cast<std::uint32_t>(this->Faces[f][k]);
      const std::uint64_t b = static_cast<std::uint32_t>(this->Faces[f][(k + 1) % 3]);
      halfEdges.emplace_back(std::min(a, b) << 32 | std::max(a, b), 3 * f + k);
    }
  }
  std::sort(halfEdges.begin(), halfEdges.end());
  this->FaceEdges.assign(static_cast<size_t>(nf), Eigen::Vector3i::Constant(-1));
  for (size_t i = 0; i < halfEdges.size();)
  {
    size_t j = i;
    const int edgeIndex = static_cast<int>(this->Edges.size());
    while (j < halfEdges.size() && halfEdges[j].first == halfEdges[i].first)
    {
      this->FaceEdges[halfEdges[j].second / 3][halfEdges[j].second % 3] = edgeIndex;
      ++j;
    }
    MeshEdge edge;
    edge.vertex0 = static_cast<int>(halfEdges[i].first >> 32);
    edge.vertex1 = static_cast<int>(halfEdges[i].first & 0xffffffffu);
    edge.face0 = halfEdges[i].second / 3;
    edge.face1 = j - i > 1 ? halfEdges[i + 1].second / 3 : -1;
    edge.nonManifold = j - i > 2;
    this->Edges.push_back(edge);
    i = j;
  }

  // Angle-weighted vertex normals: the weight of a face at a corner is the
  // corner's angle, which makes the normal independent of the triangulation.
  this->VertexNormals.assign(static_cast<size_t>(nv), Eigen::Vector3d::Zero());
  for (int f = 0; f < nf; ++f)
  {
    if (this->FaceAreas[f] <= 0.0)
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      const Eigen::Vector3d u = (this->corner(f, (k + 1) % 3) - this->corner(f, k)).normalized();
      const Eigen::Vector3d w = (this->corner(f, (k + 2) % 3) - this->corner(f, k)).normalized();
      const double angle = std::acos(std::clamp(u.dot(w), -1.0, 1.0));
      this->VertexNormals[this->Faces[f][k]] += angle * this->FaceNormals[f];
    }
  }
  for (Eigen::Vector3d& n : this->VertexNormals)
  {
    const double length = n.norm();
    n = length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
  }
}

Eigen::Vector3d TriangleMesh::pseudoNormal(int face, const Eigen::Vector3d& w) const
{
  constexpr double onFeature = 1e-9;
  for (int k = 0; k < 3; ++k)
  {
    if (w[k] >= 1.0 - onFeature)
    {
      return this->VertexNormals[this->Faces[face][k]];
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    // The weight of the corner opposite edge (k+1, k+2) vanishes on that edge.
    if (w[k] <= onFeature)
    {
      const MeshEdge& edge = this->Edges[this->FaceEdges[face][(k + 1) % 3]];
      Eigen::Vector3d n = this->FaceNormals[edge.face0];
      if (edge.face1 >= 0)
      {
        n += this->FaceNormals[edge.face1];
      }
      return n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : this->FaceNormals[face];
    }
  }
  return this->FaceNormals[face];
}

Eigen::Vector3d TriangleMesh::faceCentroid(int face) const
{
  return (this->corner(face, 0) + this->corner(face, 1) + this->corner(face, 2)) / 3.0;
}

int TriangleMesh::numberOfBoundaryEdges() const
{
  return static_cast<int>(std::count_if(
    this->Edges.begin(), this->Edges.end(), [](const MeshEdge& e) { return e.isBoundary(); }));
}

int TriangleMesh::numberOfNonManifoldEdges() const
{
  return static_cast<int>(std::count_if(
    this->Edges.begin(), this->Edges.end(), [](const MeshEdge& e) { return e.nonManifold; }));
}

double TriangleMesh::totalArea() const
{
  double area = 0.0;
  for (double a : this->FaceAreas)
  {
    area += a;
  }
  return area;
}

double TriangleMesh::signedVolume() const
{
  // Divergence theorem over tetrahedra from a reference point (the first
  // vertex, which keeps round-off small for meshes far from the origin).
  if (this->Vertices.empty())
  {
    return 0.0;
  }
  const Eigen::Vector3d& o = this->Vertices.front();
  double volume = 0.0;
  for (int f = 0; f < this->numberOfFaces(); ++f)
  {
    volume += (this->corner(f, 0) - o).dot((this->corner(f, 1) - o).cross(this->corner(f, 2) - o));
  }
  return volume / 6.0;
}

Eigen::Matrix<double, 3, 2> TriangleMesh::bounds() const
{
  Eigen::Matrix<double, 3, 2> b;
  if (this->Vertices.empty())
  {
    b.setZero();
    return b;
  }
  b.col(0) = this->Vertices.front();
  b.col(1) = this->Vertices.front();
  for (const Eigen::Vector3d& v : this->Vertices)
  {
    b.col(0) = b.col(0).cwiseMin(v);
    b.col(1) = b.col(1).cwiseMax(v);
  }
  return b;
}

TriangleMesh TriangleMesh::flipped() const
{
  std::vector<Eigen::Vector3i> reversed = this->Faces;
  for (Eigen::Vector3i& tri : reversed)
  {
    std::swap(tri[1], tri[2]);
  }
  return TriangleMesh(this->Vertices, std::move(reversed));
}

} // namespace vimlop
