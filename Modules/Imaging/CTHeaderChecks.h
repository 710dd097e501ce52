#ifndef vimlop_CTHeaderChecks_h
#define vimlop_CTHeaderChecks_h

// Checks of a CT file's header made before ITK reads it, for what ITK's
// readers let through: data shorter than the header promises (read as
// zeros), and NRRD headers that teem's parser mishandles. Each throws
// vimlop::Error "'path': problem". ITK-free: plain file reading.

#include <cstdint>
#include <string>

namespace vimlop::detail
{

/// @brief An uncompressed NIfTI-1 file holds the voxel bytes its header promises.
void checkNiftiLength(const std::string& path, std::uint64_t voxelBytes);

/// @brief A MetaImage header's data file exists and holds the voxel bytes promised.
void checkMetaImageData(const std::string& path, std::uint64_t voxelBytes);

/**
 * @brief An NRRD header has lines of at most 1024 characters (teem copied a
 * 5000-character field into a fixed buffer) and, when the data follow it in
 * the same file, ends with the blank line the format requires.
 */
void checkNrrdHeader(const std::string& path);

} // namespace vimlop::detail

#endif
