#ifndef vimlop_VTKCameraAdapter_h
#define vimlop_VTKCameraAdapter_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>

#include "VIMLOPRenderingModule.h"

class vtkCamera;

/**
 * @file VTKCameraAdapter.h
 * @brief The one place where VIMLOP's OpenCV-convention pinhole camera meets
 * VTK's camera (x right, y up, looking down -z, OpenGL clip space).
 */

namespace vimlop
{

/**
 * @brief Sets `camera` so that a render of `widthPx` x `heightPx` pixels shows
 * exactly what the pinhole `intrinsics` at `cameraToWorld` see.
 *
 * The projection is set explicitly from fx, fy, cx, cy (so non-square pixels
 * and off-centre principal points are exact), with near and far clipping
 * planes at `nearMm` and `farMm` along the optical axis.
 */
VIMLOPRENDERING_EXPORT void setVTKCamera(vtkCamera* camera, const PinholeCamera& intrinsics,
  const CameraPose& cameraToWorld, double nearMm, double farMm);

/**
 * @brief Camera depth (mm along the optical axis) of a z-buffer value in [0, 1]
 * rendered with setVTKCamera()'s projection; +infinity for the far plane.
 */
VIMLOPRENDERING_EXPORT double depthFromZBuffer(float zBuffer, double nearMm, double farMm);

} // namespace vimlop

#endif
