#ifndef vimlop_MeshFileChecks_h
#define vimlop_MeshFileChecks_h

// Private to the Imaging module (not installed): the checks of a mesh file
// made before VTK's reader sees it, for what those readers mishandle. Each
// throws vimlop::Error "'path': problem". VTK-free: plain file reading.

#include <string>

namespace vimlop::detail
{

/**
 * @brief Legacy VTK: the counts after POINTS, POLYGONS and the like at most
 * 20 000 000, and the cell lists walked: each cell's ids inside the list and
 * naming points the file has (VTK read past a list whose counts disagree).
 */
void checkLegacyVtk(const std::string& path);

/// @brief VTK XML polydata: the counts of the Piece elements at most 20 000 000.
void checkXmlPolyData(const std::string& path);

/// @brief Wavefront OBJ: every index of a face, line or point names a vertex, texture
/// coordinate or normal defined before it (VTK looked up index 0 as -1).
void checkObj(const std::string& path);

/// @brief Binary STL: the triangle count matches the file size (VTK read short files as given).
void checkStl(const std::string& path);

} // namespace vimlop::detail

#endif
