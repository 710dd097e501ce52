#ifndef vimlop_MeshTree_h
#define vimlop_MeshTree_h

#include <vimlop/Core/SurfaceLocator.h>
#include <vimlop/Core/TriangleMesh.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

/// @brief Result of a most-likely-point search: the point and its match cost.
struct MostLikelyPoint
{
  SurfacePoint surfacePoint;
  /// ½ dᵀ M⁻¹ d with d = y - z (dimensionless).
  double cost = 0.0;
};

/**
 * @brief Bounding-volume tree over the faces of a mesh for most-likely-point
 * (V2) and closest-point queries on the surface (not only the vertices).
 *
 * The most likely point of a query z with covariance M minimises
 * ½ (y - z)ᵀ M⁻¹ (y - z) over the surface. It is exact per triangle: whitening
 * by M^(-1/2) is affine, so the whitened closest point of each whitened
 * triangle gives it. Pruning uses the eigenvalue bound: any y with cost at
 * most the best cost B so far satisfies |y - z|² <= 2 B λmax(M), so tree nodes
 * farther than that from z are skipped. All queries are const and thread-safe.
 */
class MeshTree : public SurfaceLocator
{
public:
  /**
   * @brief Builds the tree over a copy of `mesh`.
   * @param leafSize faces per leaf (default 8).
   * @throws vimlop::Error if the mesh has no faces.
   */
  explicit MeshTree(const TriangleMesh& mesh, int leafSize = 8);

  const TriangleMesh& mesh() const { return this->Mesh; }

  /// @brief Euclidean closest surface point to `query` (mm).
  SurfacePoint closestPoint(const Eigen::Vector3d& query) const override;

  /**
   * @brief Most likely surface point for `z` (mm, model frame) under the
   * symmetric positive definite covariance `covariance` (mm², model frame).
   * @param hintFace a face likely to be close (e.g. the previous match), used
   * to start with a tight bound; -1 for none. It never changes the answer.
   */
  MostLikelyPoint mostLikelyPoint(
    const Eigen::Vector3d& z, const Eigen::Matrix3d& covariance, int hintFace = -1) const;

  /**
   * @brief True when the open segment from `from` to `to` crosses a face,
   * ignoring its first and last `toleranceMm` (so a segment ending on the
   * surface is not occluded by the face it ends on).
   */
  bool isSegmentOccluded(
    const Eigen::Vector3d& from, const Eigen::Vector3d& to, double toleranceMm = 1e-3) const;

  /// @brief The same search over every face, without the tree (the reference).
  static MostLikelyPoint mostLikelyPointBruteForce(
    const TriangleMesh& mesh, const Eigen::Vector3d& z, const Eigen::Matrix3d& covariance);

  /// @brief Faces evaluated so far by the queries of the calling thread (a
  /// running count, for benchmarks).
  static long long facesVisited();

private:
  /// Depth-first layout: an inner node's left child follows it directly.
  struct Node
  {
    Eigen::Vector3d lo;
    Eigen::Vector3d hi;
    int first = 0;  ///< leaf: first slot in Faces
    int count = 0;  ///< leaf: number of faces; 0 for an inner node
    int right = -1; ///< inner: index of the right child
  };

  int build(int begin, int end, std::vector<Eigen::Vector3d>& centroids);

  template <typename LeafVisitor>
  void traverse(const Eigen::Vector3d& z, double& pruneDistance2, LeafVisitor&& visit) const;

  TriangleMesh Mesh;
  int LeafSize;
  std::vector<Node> Nodes;
  std::vector<int> Faces; ///< face indices in leaf order
};

} // namespace vimlop

#endif
