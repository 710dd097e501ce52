#ifndef vimlop_FramePose_h
#define vimlop_FramePose_h

#include <vimlop/Core/CameraPose.h>

namespace vimlop
{

/**
 * @brief The pose of one video frame's camera, identified by the frame's id
 * (its index in the input sequence unless the input numbers frames itself).
 */
struct FramePose
{
  int frameId = 0;
  CameraPose cameraToWorld;
};

} // namespace vimlop

#endif
