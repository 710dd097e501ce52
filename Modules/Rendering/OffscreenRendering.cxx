#include <vimlop/Rendering/OffscreenRendering.h>

#include <vimlop/Core/Error.h>

#include <vtkAutoInit.h>
#include <vtkRenderWindow.h>
#include <vtkSmartPointer.h>

#ifdef VIMLOP_HAVE_X11
#include <X11/Xlib.h>
#endif

#include <cstdlib>
#include <cstring>
#include <mutex>

VTK_MODULE_INIT(vtkRenderingOpenGL2);

namespace vimlop
{

namespace
{

/// The start of every error of this check, for `what` the caller names.
std::string needsDisplay(const std::string& what)
{
  return what + " renders offscreen with VTK, which needs an X display here; ";
}

#ifdef VIMLOP_HAVE_X11
/// Opens one connection to the X display, once, and keeps it until the
/// process ends. An X server resets when its last client disconnects (the
/// Xvfb that `xvfb-run` starts does), and VTK aborts the process when it
/// opens a window while the server resets; each VTK window has a connection
/// of its own, so between two renderings there may be none. This one keeps
/// the server from resetting, and a display that cannot be reached becomes
/// an error instead of an abort.
void holdDisplayConnection(const std::string& what, const char* display)
{
  static std::mutex mutex;
  static Display* connection = nullptr;
  std::lock_guard<std::mutex> lock(mutex);
  if (connection)
  {
    return;
  }
  connection = XOpenDisplay(nullptr);
  if (!connection)
  {
    throw Error(needsDisplay(what) + "DISPLAY is '" + display + "' but no X server answers there");
  }
}
#endif

} // namespace

void requireOffscreenRendering(const std::string& what)
{
  // Creating the window object opens no connection; rendering would.
  const auto window = vtkSmartPointer<vtkRenderWindow>::New();
  if (std::strcmp(window->GetClassName(), "vtkXOpenGLRenderWindow") != 0)
  {
    return;
  }
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    throw Error(
      needsDisplay(what) + "none is set (on a server, run the command under xvfb-run -a)");
  }
#ifdef VIMLOP_HAVE_X11
  holdDisplayConnection(what, display);
#endif
}

} // namespace vimlop
