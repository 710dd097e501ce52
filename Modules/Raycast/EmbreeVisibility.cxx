#include <vimlop/Raycast/EmbreeVisibility.h>

#include <algorithm>

namespace vimlop
{

EmbreeVisibility::EmbreeVisibility(
  std::shared_ptr<const EmbreeScene> scene, double toleranceMm, double relativeTolerance)
  : Scene(std::move(scene))
  , ToleranceMm(toleranceMm)
  , RelativeTolerance(relativeTolerance)
{
}

void EmbreeVisibility::classify(const PinholeCamera&, const CameraPose& cameraToCT,
  const std::vector<Eigen::Vector3d>& pointsCT, std::vector<char>& visible) const
{
  std::vector<double> tolerances(pointsCT.size());
  for (size_t i = 0; i < pointsCT.size(); ++i)
  {
    const double distance = (pointsCT[i] - cameraToCT.centre).norm();
    tolerances[i] = std::max(this->ToleranceMm, this->RelativeTolerance * distance);
  }
  std::vector<char> occluded;
  this->Scene->areSegmentsOccluded(cameraToCT.centre, pointsCT, tolerances, occluded);
  visible.resize(pointsCT.size());
  for (size_t i = 0; i < pointsCT.size(); ++i)
  {
    visible[i] = occluded[i] ? 0 : 1;
  }
}

} // namespace vimlop
