#ifndef vimlop_WindowCapture_h
#define vimlop_WindowCapture_h

#include "VIMLOPRenderingModule.h"

#include <vtkSmartPointer.h>

class vtkImageData;
class vtkRenderWindow;

namespace vimlop
{

/**
 * @brief Renders `window` and returns its picture as an RGB unsigned char VTK
 * image (row 0 at the bottom) of the window's size.
 */
VIMLOPRENDERING_EXPORT vtkSmartPointer<vtkImageData> captureWindow(vtkRenderWindow* window);

} // namespace vimlop

#endif
