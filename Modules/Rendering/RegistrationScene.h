#ifndef vimlop_RegistrationScene_h
#define vimlop_RegistrationScene_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/TriangleMesh.h>

#include "VIMLOPRenderingModule.h"

#include <vtkSmartPointer.h>

#include <Eigen/Core>

#include <vector>

class vtkImageData;

namespace vimlop
{

/**
 * @brief The report's 3-D scene (the paper's Fig. 1b), rendered offscreen:
 * the model surface cut open by a plane through the data so that its inside
 * is seen, the registered SfM points in red, the registered camera path as
 * yellow arrows along the viewing directions joined by a line, and, when
 * given, the true cameras as cyan arrows.
 *
 * The view looks at the data from the side of the camera path (along the
 * cameras' mean x axis, image up roughly up) from far enough to see all of
 * it; the half of the model between the viewer and the data is cut away.
 * An orientation marker in the bottom left corner shows the CT frame's axes
 * as the view turns them, labelled L, P and S (+x, +y, +z: LPS).
 * RGB unsigned char, `widthPx` x `heightPx`, row 0 at the bottom. Needs an X
 * display.
 * @throws vimlop::Error for a mesh without faces or no points and no cameras.
 */
VIMLOPRENDERING_EXPORT vtkSmartPointer<vtkImageData> renderRegistrationScene(
  const TriangleMesh& model, const std::vector<Eigen::Vector3d>& pointsCT,
  const std::vector<CameraPose>& camerasCT, const std::vector<CameraPose>& trueCamerasCT,
  int widthPx, int heightPx);

} // namespace vimlop

#endif
