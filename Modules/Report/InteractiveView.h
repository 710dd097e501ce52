#ifndef vimlop_InteractiveView_h
#define vimlop_InteractiveView_h

// Private to the Report module: the report's interactive 3-D view.

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/TriangleMesh.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace vimlop
{

/// @brief What the interactive view shows, CT frame (LPS), mm.
struct InteractiveScene
{
  TriangleMesh model;
  std::vector<Eigen::Vector3d> pointsCT;
  std::vector<CameraPose> camerasCT;
  /// The true cameras, when the record has a truth (else empty).
  std::vector<CameraPose> trueCamerasCT;
};

/**
 * @brief Writes the files of the report's interactive 3-D view into
 * `folder`: `scene-data.js` (the scene as a script that sets
 * `window.vimlopScene`: a browser opening the report from disk may not read
 * a JSON file beside it, but it runs a script) and `view3d.js` (a small WebGL
 * viewer written for this report: drag to turn, wheel to zoom, double-click
 * to reset). Both work offline, from the result folder alone.
 * @return the HTML that shows the view (a canvas and the two scripts).
 * @throws vimlop::Error when a file cannot be written.
 */
std::string writeInteractiveView(const InteractiveScene& scene, const std::string& folder);

} // namespace vimlop

#endif
