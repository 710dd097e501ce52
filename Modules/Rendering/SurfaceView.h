#ifndef vimlop_SurfaceView_h
#define vimlop_SurfaceView_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/TriangleMesh.h>

#include "VIMLOPRenderingModule.h"

#include <vtkSmartPointer.h>

#include <memory>

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
 * contours are, and shows the registered video's view of the airway. One
 * SurfaceView keeps its render window, its mesh (with its point normals,
 * computed once) and its actor for every picture it renders, so a sequence
 * of poses costs one window and one upload of the mesh, not one per frame.
 * Needs an X display.
 */
class VIMLOPRENDERING_EXPORT SurfaceView
{
public:
  /// @throws vimlop::Error for a mesh without faces.
  explicit SurfaceView(const TriangleMesh& mesh);
  ~SurfaceView();
  SurfaceView(const SurfaceView&) = delete;
  SurfaceView& operator=(const SurfaceView&) = delete;

  /**
   * @brief The picture seen by `intrinsics` at `cameraToCT` (camera-to-CT,
   * mm): RGB unsigned char, the intrinsics' size, row 0 at the bottom.
   * @throws vimlop::Error for invalid intrinsics.
   */
  vtkSmartPointer<vtkImageData> render(
    const PinholeCamera& intrinsics, const CameraPose& cameraToCT);

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

/**
 * @brief One picture of SurfaceView (a window of its own: for many poses of
 * one mesh, keep a SurfaceView instead).
 * @throws vimlop::Error for a mesh without faces or invalid intrinsics.
 */
VIMLOPRENDERING_EXPORT vtkSmartPointer<vtkImageData> renderSurfaceView(
  const TriangleMesh& mesh, const PinholeCamera& intrinsics, const CameraPose& cameraToCT);

} // namespace vimlop

#endif
