#ifndef vimlop_PlyMeshReader_h
#define vimlop_PlyMeshReader_h

// Private to the Imaging module (not installed). VTK-free: plain file reading.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vimlop::detail
{

/// @brief The geometry of a PLY file: its vertices and its faces' vertex indices.
struct PlyMesh
{
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<std::int64_t>> faces;
};

/**
 * @brief Reads the vertices (x, y, z) and faces (vertex_indices) of a PLY
 * file, ASCII or binary of either byte order, every other element and
 * property read past. VIMLOP reads PLY itself because VTK 9.1's PLY reader
 * cannot be made safe by checks in front of it: on a truncated file, a
 * mangled header line or a missing element it read past its buffers and
 * freed pointers it never set.
 * @throws vimlop::Error "'path': problem" for what it cannot read: no PLY
 * header, an unknown format or type, counts that cannot fit in the file,
 * data that end early, a face naming a vertex the file does not have.
 */
PlyMesh readPlyMesh(const std::string& path);

} // namespace vimlop::detail

#endif
