#ifndef vimlop_TriangleMesh_h
#define vimlop_TriangleMesh_h

#include <vimlop/Core/MeshEdge.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

/**
 * @brief An indexed triangle mesh with face normals and edge-face adjacency.
 *
 * Vertices are in mm in the mesh's frame (the CT frame for airway models).
 * Face normals follow the right-hand rule on the vertex order; by VIMLOP's
 * convention a model's faces are ordered so that normals point into the air,
 * i.e. into the cavity where the endoscope is. Zero-area faces keep a zero
 * normal. The mesh is immutable once built, so derived data stay consistent.
 */
class TriangleMesh
{
public:
  TriangleMesh() = default;

  /**
   * @brief Builds the mesh and its derived data (normals, areas, edges).
   * @throws vimlop::Error for non-finite vertices, face indices out of range or
   * faces that repeat a vertex.
   */
  TriangleMesh(std::vector<Eigen::Vector3d> vertices, std::vector<Eigen::Vector3i> faces);

  const std::vector<Eigen::Vector3d>& vertices() const { return this->Vertices; }
  const std::vector<Eigen::Vector3i>& faces() const { return this->Faces; }
  /// @brief Unit face normals (zero for zero-area faces).
  const std::vector<Eigen::Vector3d>& faceNormals() const { return this->FaceNormals; }
  /// @brief Face areas in mm^2.
  const std::vector<double>& faceAreas() const { return this->FaceAreas; }
  /// @brief Every edge once, sorted by (vertex0, vertex1).
  const std::vector<MeshEdge>& edges() const { return this->Edges; }
  /// @brief Edge indices of each face: entry k is the edge from corner k to corner k + 1.
  const std::vector<Eigen::Vector3i>& faceEdges() const { return this->FaceEdges; }
  /// @brief Angle-weighted vertex normals (unit; zero at isolated vertices).
  const std::vector<Eigen::Vector3d>& vertexNormals() const { return this->VertexNormals; }

  /**
   * @brief Normal of the surface at a point given by face and barycentric
   * weights: the face normal inside, the edge's (sum of its faces' normals)
   * on an edge, the vertex's angle-weighted normal at a corner. With these
   * pseudo-normals the sign of n · (p - q), q the closest surface point to p,
   * tells inside from outside of a closed surface exactly (Baerentzen and
   * Aanaes, 2005), which the anatomical constraint (V10) relies on.
   */
  Eigen::Vector3d pseudoNormal(int face, const Eigen::Vector3d& barycentric) const;

  int numberOfVertices() const { return static_cast<int>(this->Vertices.size()); }
  int numberOfFaces() const { return static_cast<int>(this->Faces.size()); }

  /// @brief Corner `corner` (0..2) of face `face`.
  const Eigen::Vector3d& corner(int face, int corner) const
  {
    return this->Vertices[this->Faces[face][corner]];
  }
  /// @brief Centroid of face `face` (mm).
  Eigen::Vector3d faceCentroid(int face) const;

  /// @brief Number of edges with a single face (open boundary).
  int numberOfBoundaryEdges() const;
  /// @brief Number of edges shared by more than two faces.
  int numberOfNonManifoldEdges() const;
  /// @brief Total area in mm^2.
  double totalArea() const;
  /**
   * @brief Volume enclosed by a closed surface, mm^3, signed: positive when
   * the normals point out of the enclosed region, negative when they point
   * into it. An airway model (normals into the air it encloses) has a
   * negative signed volume.
   */
  double signedVolume() const;

  /// @brief Axis-aligned bounds: column 0 the minimum, column 1 the maximum corner.
  Eigen::Matrix<double, 3, 2> bounds() const;

  /// @brief The same surface with every face reversed (normals flipped).
  TriangleMesh flipped() const;

private:
  std::vector<Eigen::Vector3d> Vertices;
  std::vector<Eigen::Vector3i> Faces;
  std::vector<Eigen::Vector3d> FaceNormals;
  std::vector<double> FaceAreas;
  std::vector<MeshEdge> Edges;
  std::vector<Eigen::Vector3i> FaceEdges;
  std::vector<Eigen::Vector3d> VertexNormals;
};

} // namespace vimlop

#endif
