#ifndef vimlop_MeshFileChecks_h
#define vimlop_MeshFileChecks_h

// Private to the Imaging module (not installed): the checks of a mesh file
// made before VTK's reader sees it, for what those readers mishandle (legacy
// VTK: LegacyVtkFileCheck.h; VTK XML: VtkXmlFileCheck.h). Each throws
// vimlop::Error "'path': problem". VTK-free: plain file reading.

#include <cstdint>
#include <string>

namespace vimlop::detail
{

/// @brief VIMLOP's surfaces have 10^4 to 10^6 triangles; a file that promises
/// more points or cells than this is corrupt or not meant for VIMLOP, and VTK's
/// readers would allocate what it promises before noticing.
constexpr std::uint64_t maxMeshElements = 20000000;

/// @brief Refuses a file that promises more than maxMeshElements `what`.
void checkPromise(const std::string& path, std::uint64_t count, const std::string& what);

/// @brief Wavefront OBJ: every index of a face, line or point names a vertex, texture
/// coordinate or normal defined before it (VTK looked up index 0 as -1).
void checkObj(const std::string& path);

/// @brief Binary STL: the triangle count matches the file size (VTK read short files as given).
void checkStl(const std::string& path);

} // namespace vimlop::detail

#endif
