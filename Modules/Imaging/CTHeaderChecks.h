#ifndef vimlop_CTHeaderChecks_h
#define vimlop_CTHeaderChecks_h

// Checks of a CT file's header made before ITK reads it, for what ITK's
// readers let through: data shorter than the header promises (read as
// zeros), NRRD headers that teem's parser mishandles, and grid geometry
// ITK reads as given and no scan has. Each throws
// vimlop::Error "'path': problem". ITK-free: plain file reading.

#include <array>
#include <cstdint>
#include <string>

namespace vimlop::detail
{

/// @brief A NIfTI-1 or NIfTI-2 header (plain or gzip) has finite voxel sizes and
/// orientation; checked before ITK reads it. Returns the version, 1 or 2 (0:
/// the file cannot be opened).
int checkNiftiHeader(const std::string& path);

/// @brief An uncompressed NIfTI-1 file holds the voxel bytes its header promises.
void checkNiftiLength(const std::string& path, std::uint64_t voxelBytes);

/// @brief A MetaImage header's data file exists and holds the voxel bytes
/// promised (raw), or enough for them (compressed).
/// Called with 0 voxel bytes before MetaIO reads the header, it judges the
/// header alone: text only, MetaImage's keys only, one data file.
void checkMetaImageData(const std::string& path, std::uint64_t voxelBytes);

/// @brief Compressed data of `compressedBytes` can hold `voxelBytes`
/// (deflate expands a byte into at most 1032): a small file cannot make the
/// reader allocate gigabytes.
void checkCompressedBound(
  const std::string& path, std::uint64_t compressedBytes, std::uint64_t voxelBytes);

/// @brief An NRRD file's data (attached, or one detached file) hold the voxel
/// bytes promised: all of them raw, enough for them gzip-compressed.
void checkNrrdData(const std::string& path, std::uint64_t voxelBytes);

/**
 * @brief An NRRD header has lines of at most 1024 characters (teem copied a
 * 5000-character field into a fixed buffer) and, when the data follow it in
 * the same file, ends with the blank line the format requires.
 */
void checkNrrdHeader(const std::string& path);

/**
 * @brief Geometry no CT (and no field on a CT's grid) has, whatever the
 * format: spacing not finite, not positive or above 100 mm; origin not
 * finite or beyond 1 km; direction columns not orthonormal.
 */
void checkGridGeometry(const std::string& path, const std::array<double, 3>& spacingMm,
  const std::array<double, 3>& originMm, const std::array<double, 9>& direction);

} // namespace vimlop::detail

#endif
