#include "OffscreenRendering.h"

#include "Error.h"

#include <vtkAutoInit.h>
#include <vtkRenderWindow.h>
#include <vtkSmartPointer.h>

#include <cstdlib>
#include <cstring>

VTK_MODULE_INIT(vtkRenderingOpenGL2);

namespace vimlop
{

void requireOffscreenRendering(const std::string& what)
{
  const char* display = std::getenv("DISPLAY");
  if (display && *display)
  {
    return;
  }
  // Creating the window object opens no connection; rendering would.
  const auto window = vtkSmartPointer<vtkRenderWindow>::New();
  if (std::strcmp(window->GetClassName(), "vtkXOpenGLRenderWindow") == 0)
  {
    throw Error(what +
      " renders offscreen with VTK, which needs an X display here; none is set "
      "(on a server, run the command under xvfb-run -a)");
  }
}

} // namespace vimlop
