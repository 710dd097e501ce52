#ifndef vimlop_CraniumAirway_h
#define vimlop_CraniumAirway_h

// The nasal airway of the real head CT that Debian's invesalius-examples
// ships (installed by CMake/install-dependencies.sh), segmented and meshed
// with the defaults of `vimlop segment` (about 2 s): the model of the tests
// that need a real airway.

#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Imaging/AirwaySegmentation.h>
#include <vimlop/Imaging/AirwaySurface.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>

#include <vtkPolyData.h>

#include <string>

namespace vimlop::fixtures
{

inline const std::string& craniumPath()
{
  static const std::string path = "/usr/share/doc/invesalius-examples/examples/Cranium.inv3";
  return path;
}

/// @brief The Cranium airway: 30000 triangles, CT frame (LPS, mm), normals into the air.
inline TriangleMesh craniumAirwayMesh()
{
  const CTVolume ct = readCTVolume(craniumPath());
  const AirwaySegmentation airway = AirwaySegmentation::compute(ct, AirwaySegmentationOptions());
  const AirwaySurface surface = AirwaySurface::compute(airway.label, AirwaySurfaceOptions());
  return toTriangleMesh(surface.surface);
}

} // namespace vimlop::fixtures

#endif
