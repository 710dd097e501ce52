#ifndef vimlop_FrameContoursIO_h
#define vimlop_FrameContoursIO_h

#include <vimlop/Video/FrameContours.h>

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief Writes `frames` as the "vimlop-contours" JSON file (version 1) of
 * `vimlop contours`: per frame its name and points [u, v, nu, nv] (pixels
 * with the centre of the top-left pixel at (0, 0); the unit normal from the
 * near, occluding side to the far side), and the pictures' "width",
 * "height" and "undistorted". Written atomically.
 * @throws vimlop::Error if the file cannot be written.
 */
void writeFrameContours(const std::vector<FrameContours>& frames,
  const FrameContoursPictures& pictures, const std::string& path);

/**
 * @brief Reads a file written by writeFrameContours(); `pictures`, when
 * given, receives what it says of the pictures.
 * @throws vimlop::Error naming the file: missing, not JSON, another format,
 * a malformed frame or point, a normal that is not a unit vector.
 */
std::vector<FrameContours> readFrameContours(
  const std::string& path, FrameContoursPictures* pictures = nullptr);

/// @brief `frame` (8-bit BGR) with each point drawn as a dot and a short
/// tick along its normal, towards the far side.
cv::Mat drawFrameContours(const cv::Mat& frame, const std::vector<ContourPoint>& points);

} // namespace vimlop

#endif
