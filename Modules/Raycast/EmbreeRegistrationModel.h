#ifndef vimlop_EmbreeRegistrationModel_h
#define vimlop_EmbreeRegistrationModel_h

#include <vimlop/Core/RegistrationModel.h>

namespace vimlop
{

/**
 * @brief A registration model whose visibility (V4) and closest-point (V10)
 * queries go through one Embree scene over `mesh`: the fast configuration.
 */
RegistrationModel makeEmbreeRegistrationModel(const TriangleMesh& mesh);

} // namespace vimlop

#endif
