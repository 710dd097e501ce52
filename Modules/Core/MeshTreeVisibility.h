#ifndef vimlop_MeshTreeVisibility_h
#define vimlop_MeshTreeVisibility_h

#include <vimlop/Core/ContourVisibility.h>
#include <vimlop/Core/MeshTree.h>

#include <memory>

namespace vimlop
{

/**
 * @brief Visibility by segment-occlusion tests on Core's own MeshTree (V4).
 *
 * Dependency-free and exact in double precision; slower than the Embree
 * backend, it serves as the reference and where Embree is not wanted. The
 * tolerance ignored at the segment's ends is max(toleranceMm, relative
 * tolerance x distance), because contour samples lie on mesh edges and
 * single rays graze the faces beside them.
 */
class MeshTreeVisibility : public ContourVisibility
{
public:
  explicit MeshTreeVisibility(std::shared_ptr<const MeshTree> tree, double toleranceMm = 1e-3,
    double relativeTolerance = 1e-4);

  void classify(const PinholeCamera& intrinsics, const CameraPose& cameraToCT,
    const std::vector<Eigen::Vector3d>& pointsCT, std::vector<char>& visible) const override;
  bool isThreadSafe() const override { return true; }

private:
  std::shared_ptr<const MeshTree> Tree;
  double ToleranceMm;
  double RelativeTolerance;
};

} // namespace vimlop

#endif
