#ifndef vimlop_EmbreeVisibility_h
#define vimlop_EmbreeVisibility_h

#include <vimlop/Core/ContourVisibility.h>
#include <vimlop/Raycast/EmbreeScene.h>

#include <memory>

namespace vimlop
{

/**
 * @brief Contour visibility by Embree ray-occlusion tests (V4, the fast path).
 *
 * A point is visible when the segment from the camera centre to it crosses no
 * face, ignoring its last max(toleranceMm, relativeTolerance x distance): the
 * samples lie on mesh edges, where the rays graze the faces beside them, and
 * Embree traverses in single precision.
 */
class EmbreeVisibility : public ContourVisibility
{
public:
  explicit EmbreeVisibility(std::shared_ptr<const EmbreeScene> scene, double toleranceMm = 1e-3,
    double relativeTolerance = 1e-4);

  void classify(const PinholeCamera& intrinsics, const CameraPose& cameraToCT,
    const std::vector<Eigen::Vector3d>& pointsCT, std::vector<char>& visible) const override;
  bool isThreadSafe() const override { return true; }

private:
  std::shared_ptr<const EmbreeScene> Scene;
  double ToleranceMm;
  double RelativeTolerance;
};

} // namespace vimlop

#endif
