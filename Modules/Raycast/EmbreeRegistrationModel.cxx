#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <vimlop/Raycast/EmbreeScene.h>
#include <vimlop/Raycast/EmbreeVisibility.h>

namespace vimlop
{

RegistrationModel makeEmbreeRegistrationModel(const TriangleMesh& mesh)
{
  RegistrationModel model(mesh);
  auto scene = std::make_shared<EmbreeScene>(mesh);
  model.setVisibility(std::make_shared<EmbreeVisibility>(scene));
  model.setLocator(scene);
  return model;
}

} // namespace vimlop
