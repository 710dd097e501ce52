#include <vimlop/Core/RegistrationModel.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/MeshTreeVisibility.h>

namespace vimlop
{

RegistrationModel::RegistrationModel(const TriangleMesh& mesh)
  : Tree(std::make_shared<MeshTree>(mesh))
{
  this->Visibility = std::make_shared<MeshTreeVisibility>(this->Tree);
  this->Locator = this->Tree;
}

void RegistrationModel::setVisibility(std::shared_ptr<const ContourVisibility> visibility)
{
  if (!visibility)
  {
    throw Error("registration model: no visibility backend given");
  }
  this->Visibility = std::move(visibility);
}

void RegistrationModel::setLocator(std::shared_ptr<const SurfaceLocator> locator)
{
  if (!locator)
  {
    throw Error("registration model: no closest-point backend given");
  }
  this->Locator = std::move(locator);
}

bool RegistrationModel::isInside(const Eigen::Vector3d& point) const
{
  const SurfacePoint closest = this->Locator->closestPoint(point);
  if (!closest.isValid())
  {
    return false;
  }
  const Eigen::Vector3d n = this->mesh().pseudoNormal(closest.face, closest.barycentric);
  return n.dot(point - closest.point) >= 0.0;
}

} // namespace vimlop
