#include <vimlop/Core/OrientNormalsIntoAir.h>

#include <vimlop/Core/Error.h>

namespace vimlop
{

TriangleMesh orientNormalsIntoAir(const TriangleMesh& mesh, std::string* note)
{
  if (mesh.numberOfFaces() == 0)
  {
    throw Error("orient normals into the air: the mesh has no faces");
  }
  const bool closed = mesh.numberOfBoundaryEdges() == 0;
  const bool flip = closed && mesh.signedVolume() > 0.0;
  if (note)
  {
    *note = flip ? "the surface's normals point out of the air it encloses; flipped them"
      : closed   ? ""
                 : "the surface is open, so the side of the air cannot be told from it; kept "
                   "its face order (its normals must point into the air)";
  }
  return flip ? mesh.flipped() : mesh;
}

} // namespace vimlop
