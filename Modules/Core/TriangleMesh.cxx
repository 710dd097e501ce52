#include "TriangleMesh.h"

#include "Error.h"

#include <Eigen/Dense>

#include <algorithm>
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

  // Edge-face adjacency by sorting (edge key, face) pairs: O(F log F), no hashing.
  std::vector<std::pair<std::uint64_t, int>> halfEdges;
  halfEdges.reserve(3 * static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint64_t a = static_cast<std::uint32_t>(this->Faces[f][k]);
      const std::uint64_t b = static_cast<std::uint32_t>(this->Faces[f][(k + 1) % 3]);
      halfEdges.emplace_back(std::min(a, b) << 32 | std::max(a, b), f);
    }
  }
  std::sort(halfEdges.begin(), halfEdges.end());
  for (size_t i = 0; i < halfEdges.size();)
  {
    size_t j = i;
    while (j < halfEdges.size() && halfEdges[j].first == halfEdges[i].first)
    {
      ++j;
    }
    MeshEdge edge;
    edge.vertex0 = static_cast<int>(halfEdges[i].first >> 32);
    edge.vertex1 = static_cast<int>(halfEdges[i].first & 0xffffffffu);
    edge.face0 = halfEdges[i].second;
    edge.face1 = j - i > 1 ? halfEdges[i + 1].second : -1;
    edge.nonManifold = j - i > 2;
    this->Edges.push_back(edge);
    i = j;
  }
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
