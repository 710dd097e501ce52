#ifndef vimlop_FramePoseIO_h
#define vimlop_FramePoseIO_h

#include <vimlop/Core/FramePose.h>

#include "VIMLOPImagingModule.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

/**
 * @file FramePoseIO.h
 * @brief Camera poses as JSON, e.g. the canonical template poses of V13.
 *
 * The format:
 * @code{.json}
 * {
 *   "frame": "CT (LPS, mm); camera x right, y down, z forward",
 *   "poses": [
 *     { "frame_id": 0, "camera_to_ct": [ r00, r01, r02, cx, r10, r11, r12, cy,
 *                                        r20, r21, r22, cz, 0, 0, 0, 1 ] }
 *   ]
 * }
 * @endcode
 * `camera_to_ct` is the 4x4 camera-to-CT matrix in row-major order: the
 * columns of its rotation are the camera axes in the CT frame (OpenCV
 * convention) and its last column the optical centre in mm (see CameraPose).
 * "frame" is informative and optional; other keys are ignored.
 */

namespace vimlop
{

/**
 * @brief Reads the poses of a JSON pose file, in file order.
 * @throws vimlop::Error naming the file and the problem: missing, not JSON,
 * no "poses" array, an entry without "frame_id" or with a "camera_to_ct"
 * that is not 16 numbers, or a matrix that is not a rigid transform.
 */
VIMLOPIMAGING_EXPORT std::vector<FramePose> readFramePoses(const std::string& path);

/**
 * @brief The poses in the format above, as JSON ("frame" and "poses"), for
 * writers that add keys of their own (readers ignore them).
 */
VIMLOPIMAGING_EXPORT nlohmann::json framePosesJson(const std::vector<FramePose>& poses);

/**
 * @brief Writes poses in the format above (framePosesJson()), atomically: the
 * file is the old one or the complete new one, never half written.
 * @throws vimlop::Error if the file cannot be written.
 */
VIMLOPIMAGING_EXPORT void writeFramePoses(
  const std::vector<FramePose>& poses, const std::string& path);

} // namespace vimlop

#endif
