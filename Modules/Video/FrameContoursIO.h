#ifndef vimlop_FrameContoursIO_h
#define vimlop_FrameContoursIO_h

#include <vimlop/Core/ContourPoint.h>

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace vimlop
{

/// @brief The contour points detected in one frame of a sequence.
struct FrameContours
{
  /// The frame's file name (FrameSequence::name).
  std::string name;
  std::vector<ContourPoint> points;
};

/**
 * @brief Writes `frames` as the "vimlop-contours" JSON file (version 1) of
 * `vimlop contours`: per frame its name and points [u, v, nu, nv] (pixels
 * with the centre of the top-left pixel at (0, 0); the unit normal from the
 * near, occluding side to the far side). Written atomically.
 * @throws vimlop::Error if the file cannot be written.
 */
void writeFrameContours(const std::vector<FrameContours>& frames, const std::string& path);

/// @brief `frame` (8-bit BGR) with each point drawn as a dot and a short
/// tick along its normal, towards the far side.
cv::Mat drawFrameContours(const cv::Mat& frame, const std::vector<ContourPoint>& points);

} // namespace vimlop

#endif
