#ifndef vimlop_SurfaceLocator_h
#define vimlop_SurfaceLocator_h

#include <vimlop/Core/SurfacePoint.h>

#include <Eigen/Core>

namespace vimlop
{

/**
 * @brief Finds the closest surface point of a model (Euclidean), as the
 * anatomical constraint (V10) needs. Implemented by MeshTree (Core) and by
 * EmbreeScene (Raycast). Implementations are safe to call from several
 * threads at once.
 */
class SurfaceLocator
{
public:
  virtual ~SurfaceLocator() = default;

  /// @brief The closest surface point to `query` (mm, model frame).
  virtual SurfacePoint closestPoint(const Eigen::Vector3d& query) const = 0;
};

} // namespace vimlop

#endif
