#ifndef vimlop_ModelLoading_h
#define vimlop_ModelLoading_h

#include "TriangleMesh.h"

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

} // namespace vimlop

#endif
