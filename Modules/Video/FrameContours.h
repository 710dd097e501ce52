#ifndef vimlop_FrameContours_h
#define vimlop_FrameContours_h

#include <vimlop/Core/ContourPoint.h>

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

/// @brief What a contours file says of the pictures its points are in.
struct FrameContoursPictures
{
  /// The frames' size, px (0: not recorded, e.g. by an older version).
  int widthPx = 0;
  int heightPx = 0;
  /// True when the points are in the frames undistorted with their
  /// intrinsics (as the registration sees them), false when in the frames
  /// as recorded.
  bool undistorted = false;
};

} // namespace vimlop

#endif
