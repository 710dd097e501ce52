#include <vimlop/Core/MeshTreeVisibility.h>

#include <algorithm>

namespace vimlop
{

MeshTreeVisibility::MeshTreeVisibility(
  std::shared_ptr<const MeshTree> tree, double toleranceMm, double relativeTolerance)
  : Tree(std::move(tree))
  , ToleranceMm(toleranceMm)
  , RelativeTolerance(relativeTolerance)
{
}

void MeshTreeVisibility::classify(const PinholeCamera&, const CameraPose& cameraToCT,
  const std::vector<Eigen::Vector3d>& pointsCT, std::vector<char>& visible) const
{
  visible.resize(pointsCT.size());
  for (size_t i = 0; i < pointsCT.size(); ++i)
  {
    const double distance = (pointsCT[i] - cameraToCT.centre).norm();
    const double tolerance = std::max(this->ToleranceMm, this->RelativeTolerance * distance);
    visible[i] = this->Tree->isSegmentOccluded(cameraToCT.centre, pointsCT[i], tolerance) ? 0 : 1;
  }
}

} // namespace vimlop
