#ifndef vimlop_OffscreenRendering_h
#define vimlop_OffscreenRendering_h

#include "VIMLOPRenderingModule.h"

#include <string>

namespace vimlop
{

/**
 * @brief Checks, before anything is rendered, that VTK can render offscreen
 * here: a VTK built for X11 (as Debian's) needs an X display even offscreen,
 * and aborts the process when it has none. With X11 it also holds one
 * connection to the display until the process ends, so that the X server
 * (xvfb-run's Xvfb) does not reset between two renderings, which would make
 * VTK abort. Call it once before rendering; later calls are cheap.
 * @throws vimlop::Error "`what` renders offscreen with VTK, which needs an X
 * display here; ..." when VTK's render window is an X11 one and DISPLAY is
 * not set or no X server answers there.
 */
VIMLOPRENDERING_EXPORT void requireOffscreenRendering(const std::string& what);

} // namespace vimlop

#endif
