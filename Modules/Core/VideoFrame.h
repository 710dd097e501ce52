#ifndef vimlop_VideoFrame_h
#define vimlop_VideoFrame_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/ContourPoint.h>
#include <vimlop/Core/PinholeCamera.h>

#include <vector>

namespace vimlop
{

/**
 * @brief One video frame as the registration sees it (V1): its camera in the
 * SfM frame and its oriented contour points.
 */
struct VideoFrame
{
  int frameId = 0;
  PinholeCamera intrinsics;
  /// Camera pose in the SfM frame (centre in SfM units).
  CameraPose cameraToSfm;
  std::vector<ContourPoint> contour;
};

} // namespace vimlop

#endif
