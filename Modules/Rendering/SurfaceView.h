#ifndef vimlop_SurfaceView_h
#define vimlop_SurfaceView_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/TriangleMesh.h>

#include "VIMLOPRenderingModule.h"

#include <vtkSmartPointer.h>

class vtkImageData;

namespace vimlop
{

/**
 * @brief A plain offscreen picture of a model as a pinhole camera sees it:
 * smooth-shaded tissue colour, lit by a light at the optical centre that
 * fades with distance, black where no surface is seen.
 *
 * It stands in for the video picture of simulated data that has none (P1),
 * so that contour overlays have a background that shows where the true
 * contours are. RGB unsigned char, the intrinsics' size, row 0 at the bottom.
 * Needs an X display.
 * @throws vimlop::Error for a mesh without faces or invalid intrinsics.
 */
VIMLOPRENDERING_EXPORT vtkSmartPointer<vtkImageData> renderSurfaceView(
  const TriangleMesh& mesh, const PinholeCamera& intrinsics, const CameraPose& cameraToCT);

} // namespace vimlop

#endif
