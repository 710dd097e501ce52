#ifndef vimlop_EmbreeScene_h
#define vimlop_EmbreeScene_h

#include <vimlop/Core/SurfaceLocator.h>
#include <vimlop/Core/SurfacePoint.h>
#include <vimlop/Core/TriangleMesh.h>

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace vimlop
{

/**
 * @brief Spatial queries on a triangle mesh through an Embree BVH.
 *
 * Answers closest-point queries (for the anatomical constraint, V10) and
 * segment-occlusion queries (for contour visibility, V4). Embree traverses in
 * single precision; the final closest point is computed in double precision
 * on the candidate triangles. All queries are const and safe to call from
 * several threads at once. Embree's headers stay out of this header.
 */
class EmbreeScene : public SurfaceLocator
{
public:
  /**
   * @brief Builds the BVH over a copy of `mesh`.
   * @throws vimlop::Error if the mesh has no faces or Embree fails.
   */
  explicit EmbreeScene(const TriangleMesh& mesh);
  ~EmbreeScene() override;
  EmbreeScene(EmbreeScene&&) noexcept;
  EmbreeScene& operator=(EmbreeScene&&) noexcept;
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// @brief The mesh the scene was built from.
  const TriangleMesh& mesh() const;

  /**
   * @brief The point of the surface closest to `query` (mm).
   * @return an invalid SurfacePoint (face -1) when nothing lies within `maxDistanceMm`.
   */
  SurfacePoint closestPoint(const Eigen::Vector3d& query, double maxDistanceMm) const;

  /// @brief The closest surface point, at any distance (SurfaceLocator, V10).
  SurfacePoint closestPoint(const Eigen::Vector3d& query) const override
  {
    return this->closestPoint(query, std::numeric_limits<double>::infinity());
  }

  /**
   * @brief True when the open segment from `from` to `to` crosses the surface.
   *
   * The first and last `toleranceMm` of the segment are ignored, so a segment
   * that ends on the surface (a contour sample seen from a camera) is not
   * occluded by the face it lies on.
   */
  bool isSegmentOccluded(
    const Eigen::Vector3d& from, const Eigen::Vector3d& to, double toleranceMm = 1e-3) const;

  /**
   * @brief isSegmentOccluded() for many segments from one point, as a coherent
   * ray stream (faster than one query at a time): sets `occluded[i]` for the
   * segment from `from` to `to[i]`, ignoring `toleranceMm[i]` at both ends.
   */
  void areSegmentsOccluded(const Eigen::Vector3d& from, const std::vector<Eigen::Vector3d>& to,
    const std::vector<double>& toleranceMm, std::vector<char>& occluded) const;

  /**
   * @brief First surface point hit by the ray `origin + t * direction`,
   * `t` in (0, maxDistanceMm] for a unit `direction`.
   * @throws vimlop::Error for a non-finite origin or direction, a zero
   * direction or a negative distance (Embree would abort on them).
   */
  std::optional<SurfacePoint> castRay(const Eigen::Vector3d& origin,
    const Eigen::Vector3d& direction,
    double maxDistanceMm = std::numeric_limits<double>::infinity()) const;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

} // namespace vimlop

#endif
