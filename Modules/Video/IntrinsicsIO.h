#ifndef vimlop_IntrinsicsIO_h
#define vimlop_IntrinsicsIO_h

#include <vimlop/Core/PinholeCamera.h>

#include <string>

namespace vimlop
{

/**
 * @brief Reads camera intrinsics from an OpenCV FileStorage file (`.yaml`,
 * `.yml`, `.json`, `.xml`).
 *
 * Two layouts are accepted: OpenCV's calibration output (`image_width`,
 * `image_height`, `camera_matrix` as a 3x3 matrix, optional
 * `distortion_coefficients`), or plain numbers `fx`, `fy`, `cx`, `cy`,
 * `width`, `height` (optional `distortion` list). Pixel conventions are
 * OpenCV's (see PinholeCamera). In both, an optional `distortion_model`
 * names how the coefficients are read: `plumb_bob` or `radial_tangential`
 * (OpenCV's default model, also when the entry is absent), or `fisheye` or
 * `equidistant` (ROS camera_info's name; OpenCV's cv::fisheye, exactly 4
 * coefficients k1..k4).
 *
 * @throws vimlop::Error naming the file and the missing or invalid entry.
 */
PinholeCamera readIntrinsics(const std::string& path);

/**
 * @brief Writes intrinsics in OpenCV's calibration layout; format by
 * extension. A fisheye lens is written with `distortion_model: fisheye`; the
 * default model is not named, so that such files stay as they were.
 * @throws vimlop::Error for an unsupported extension or a failed write.
 */
void writeIntrinsics(const PinholeCamera& camera, const std::string& path);

/// @brief True when `path` has an extension readIntrinsics() accepts.
bool isIntrinsicsPath(const std::string& path);

} // namespace vimlop

#endif
