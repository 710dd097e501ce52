#ifndef vimlop_SfmReconstructionIO_h
#define vimlop_SfmReconstructionIO_h

#include <vimlop/Video/SfmReconstruction.h>

#include <string>

/**
 * @file SfmReconstructionIO.h
 * @brief VIMLOP's SfM file: a JSON document that later stages (registration)
 * read back.
 *
 * Layout (lengths in SfM units, pixels with the centre of the top-left pixel
 * at (0, 0), cameras camera-to-SfM with OpenCV axes):
 * ```
 * {"format": "vimlop-sfm", "version": 1, "source": "builtin" | "colmap",
 *  "rms_reprojection_error_px": 0.31,
 *  "tracker_scale_mm_per_unit": 0.52,                   // 0 when no tracker was used
 *  "frames": [{"name": "frame000.png", "registered": true,
 *              "intrinsics": {"fx": .., "fy": .., "cx": .., "cy": .., "width": .., "height": ..,
 *                             "distortion": [k1, k2, p1, p2, ...],
 *                             "distortion_model": "fisheye"},   // only for a fisheye (k1..k4)
 *              "rotation": [r00, r01, r02, r10, ..., r22],   // camera axes as columns, row-major
 *              "centre": [x, y, z]}, ...],
 *  "points": [{"position": [x, y, z],
 *              "covariance": [xx, xy, xz, yy, yz, zz],        // SfM units², SfM axes
 *              "colour": [r, g, b], "error_px": 0.2,
 *              "observations": [[frame, u, v], ...]}, ...]}
 * ```
 */

namespace vimlop
{

/// @brief Writes `reconstruction` to `path` (JSON, the layout above).
/// @throws vimlop::Error if the file cannot be written.
void writeSfmReconstruction(const SfmReconstruction& reconstruction, const std::string& path);

/**
 * @brief Reads a file written by writeSfmReconstruction().
 * @throws vimlop::Error naming the file and the problem (missing, not JSON,
 * wrong format, a missing or malformed entry, dangling frame indices).
 */
SfmReconstruction readSfmReconstruction(const std::string& path);

} // namespace vimlop

#endif
