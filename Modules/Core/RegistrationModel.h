#ifndef vimlop_RegistrationModel_h
#define vimlop_RegistrationModel_h

#include <vimlop/Core/ContourVisibility.h>
#include <vimlop/Core/MeshTree.h>
#include <vimlop/Core/SurfaceLocator.h>
#include <vimlop/Core/TriangleMesh.h>

#include <memory>

namespace vimlop
{

/**
 * @brief The model side of a registration: the CT airway surface (normals
 * into the air) with its search tree, and the backends for contour
 * visibility (V4) and closest points (V10).
 *
 * By default both backends use Core's own MeshTree; the Raycast module's
 * Embree backends are faster (see EmbreeScene, EmbreeVisibility), and the
 * Rendering module offers the paper's z-buffer visibility. Backends must be
 * built over the same mesh.
 */
class RegistrationModel
{
public:
  /// @throws vimlop::Error if the mesh has no faces.
  explicit RegistrationModel(const TriangleMesh& mesh);

  const TriangleMesh& mesh() const { return this->Tree->mesh(); }
  const MeshTree& tree() const { return *this->Tree; }
  std::shared_ptr<const MeshTree> sharedTree() const { return this->Tree; }

  const ContourVisibility& visibility() const { return *this->Visibility; }
  void setVisibility(std::shared_ptr<const ContourVisibility> visibility);

  const SurfaceLocator& locator() const { return *this->Locator; }
  void setLocator(std::shared_ptr<const SurfaceLocator> locator);

  /**
   * @brief True when `point` (mm, CT) lies on the air side of the surface:
   * the pseudo-normal at its closest surface point faces it (V10).
   */
  bool isInside(const Eigen::Vector3d& point) const;

private:
  std::shared_ptr<const MeshTree> Tree;
  std::shared_ptr<const ContourVisibility> Visibility;
  std::shared_ptr<const SurfaceLocator> Locator;
};

} // namespace vimlop

#endif
