#ifndef vimlop_ModelLoading_h
#define vimlop_ModelLoading_h

#include <vimlop/Core/TriangleMesh.h>

#include <map>
#include <string>

namespace vimlop
{

/**
 * @brief Reads an airway surface for registration: triangles in the CT frame
 * with normals into the air.
 *
 * A closed mesh whose normals point out of the air it encloses (positive
 * signed volume) is flipped, with a note on stderr, since files from other
 * tools often use the outward convention.
 * @throws vimlop::Error if the file cannot be read or has no triangles.
 */
TriangleMesh loadAirwayMesh(const std::string& path);

/**
 * @brief The airway surface of a CT, segmented and meshed with the defaults of
 * `vimlop segment` (see AirwaySegmentation and AirwaySurface). The reader's
 * warnings go to stderr; `identity`, when given, receives CTVolume::identity.
 * @throws vimlop::Error if the CT cannot be read or holds no airway.
 */
TriangleMesh segmentAirwayMesh(
  const std::string& ctPath, std::map<std::string, std::string>* identity = nullptr);

/// @brief loadAirwayMesh(meshPath) or, when it is empty, segmentAirwayMesh(ctPath, identity).
TriangleMesh airwayMeshFrom(const std::string& meshPath, const std::string& ctPath,
  std::map<std::string, std::string>* identity = nullptr);

} // namespace vimlop

#endif
