#include "ModelLoading.h"

#include "Error.h"
#include "MeshIO.h"
#include "PolyDataConversion.h"

#include <vtkPolyData.h>

#include <iostream>

namespace vimlop
{

TriangleMesh loadAirwayMesh(const std::string& path)
{
  const vtkSmartPointer<vtkPolyData> polyData = readPolyData(path);
  TriangleMesh mesh;
  try
  {
    mesh = toTriangleMesh(polyData);
  }
  catch (const Error& e)
  {
    throw Error("'" + path + "': " + e.what());
  }
  if (mesh.numberOfBoundaryEdges() == 0 && mesh.signedVolume() > 0.0)
  {
    std::cerr << "vimlop: note: '" << path
              << "' has normals pointing out of the air it encloses; flipping them\n";
    mesh = mesh.flipped();
  }
  return mesh;
}

} // namespace vimlop
