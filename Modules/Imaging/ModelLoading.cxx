#include <vimlop/Imaging/ModelLoading.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/OrientNormalsIntoAir.h>
#include <vimlop/Imaging/AirwaySegmentation.h>
#include <vimlop/Imaging/AirwaySurface.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>

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
    throwFileError(path, std::string(e.what()));
  }
  std::string note;
  mesh = orientNormalsIntoAir(mesh, &note);
  if (!note.empty())
  {
    std::cerr << "vimlop: note: '" << path << "': " << note << "\n";
  }
  return mesh;
}

TriangleMesh segmentAirwayMesh(
  const std::string& ctPath, std::map<std::string, std::string>* identity)
{
  const CTVolume ct = readCTVolume(ctPath);
  for (const std::string& warning : ct.warnings)
  {
    std::cerr << "vimlop: warning: '" << ctPath << "': " << warning << "\n";
  }
  if (identity)
  {
    *identity = ct.identity;
  }
  const AirwaySegmentation airway = AirwaySegmentation::compute(ct, AirwaySegmentationOptions());
  const AirwaySurface surface = AirwaySurface::compute(airway.label, AirwaySurfaceOptions());
  std::cerr << "vimlop: segmented the airway of '" << ctPath << "': " << surface.triangles
            << " triangles, " << surface.enclosedVolumeMm3 / 1000.0 << " cm^3\n";
  return toTriangleMesh(surface.surface);
}

TriangleMesh airwayMeshFrom(const std::string& meshPath, const std::string& ctPath,
  std::map<std::string, std::string>* identity)
{
  if (meshPath.empty() == ctPath.empty())
  {
    throw Error("give exactly one of --mesh and --ct");
  }
  return meshPath.empty() ? segmentAirwayMesh(ctPath, identity) : loadAirwayMesh(meshPath);
}

} // namespace vimlop
