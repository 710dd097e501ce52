#ifndef vimlop_OrientNormalsIntoAir_h
#define vimlop_OrientNormalsIntoAir_h

#include <vimlop/Core/TriangleMesh.h>

#include <string>

namespace vimlop
{

/**
 * @brief The mesh with its normals into the air (Documentation/Conventions.md), by
 * the one rule every loader applies: a closed surface whose signed volume is
 * positive has normals pointing out of the air it encloses, and is flipped;
 * any other mesh is kept as it is.
 *
 * An open surface encloses nothing, so its air side cannot be told from the
 * mesh alone: its faces keep their order and must already point into the air.
 * The winding must be consistent (neighbouring faces agree), as every test of
 * this rule assumes.
 *
 * @param note when given, set to a sentence for the user when the mesh was
 *   flipped or is open (the orientation was not checked), else cleared
 * @throws vimlop::Error for a mesh without faces.
 */
TriangleMesh orientNormalsIntoAir(const TriangleMesh& mesh, std::string* note = nullptr);

} // namespace vimlop

#endif
