#ifndef vtkVIMLOPSilhouetteRenderer_h
#define vtkVIMLOPSilhouetteRenderer_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/TriangleMesh.h>

#include "VIMLOPRenderingModule.h"

#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkSmartPointer.h>

class vtkActor;
class vtkImageData;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkPolyDataSilhouette;
class vtkRenderer;
class vtkRenderWindow;

/**
 * @brief Draws the visible occluding contours of a model as a pinhole camera
 * sees them, by offscreen rendering with VTK (V3 drawn, for reports and as an
 * independent check of Core's extraction).
 *
 * VTK's own vtkPolyDataSilhouette picks the contour edges: edges whose two
 * faces face opposite ways as seen from the camera centre (the same rule as
 * vimlop::extractOccludingContours, evaluated at the edge's midpoint instead
 * of the faces' centroids). They are drawn as one-pixel lines over the
 * surface, which is drawn in the background colour and pushed back by a
 * polygon offset: the z-buffer hides the contour parts that the surface
 * covers, and the faces beside a contour edge, which graze the viewing rays,
 * do not hide the edge itself. No anti-aliasing: a pixel is on or off.
 *
 * Needs an X display (use `xvfb-run -a` on servers).
 */
class VIMLOPRENDERING_EXPORT vtkVIMLOPSilhouetteRenderer : public vtkObject
{
public:
  static vtkVIMLOPSilhouetteRenderer* New();
  vtkTypeMacro(vtkVIMLOPSilhouetteRenderer, vtkObject)
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * @brief The model (CT frame, mm).
   * @throws vimlop::Error for a mesh without faces.
   */
  void SetMesh(const vimlop::TriangleMesh& mesh);

  ///@{
  /// Near and far clipping distances along the optical axis, mm (defaults 0.1 and 300).
  vtkSetClampMacro(NearClipMm, double, 1e-4, 1e6);
  vtkGetMacro(NearClipMm, double);
  vtkSetClampMacro(FarClipMm, double, 1e-3, 1e9);
  vtkGetMacro(FarClipMm, double);
  ///@}

  ///@{
  /// Width of the drawn contour lines, pixels (default 1).
  vtkSetClampMacro(LineWidthPx, double, 1.0, 10.0);
  vtkGetMacro(LineWidthPx, double);
  ///@}

  /**
   * @brief Renders the visible contours seen by `intrinsics` at `cameraToCT`.
   *
   * @return a one-component unsigned char image of the intrinsics' size, 255
   * on contour pixels and 0 elsewhere, in VTK's image orientation: row 0 is
   * the bottom row, so pixel (u, v) of the OpenCV convention is at
   * (u, heightPx - 1 - v). Spacing 1, origin 0.
   * @throws vimlop::Error without a mesh or with invalid intrinsics.
   */
  vtkSmartPointer<vtkImageData> RenderContours(
    const vimlop::PinholeCamera& intrinsics, const vimlop::CameraPose& cameraToCT);

  /// @brief The contour edges of the last rendering, before hiding (lines, CT frame, mm).
  vtkPolyData* GetContourEdges();

protected:
  vtkVIMLOPSilhouetteRenderer();
  ~vtkVIMLOPSilhouetteRenderer() override;

private:
  vtkVIMLOPSilhouetteRenderer(const vtkVIMLOPSilhouetteRenderer&) = delete;
  void operator=(const vtkVIMLOPSilhouetteRenderer&) = delete;

  double NearClipMm = 0.1;
  double FarClipMm = 300.0;
  double LineWidthPx = 1.0;
  bool HasMesh = false;
  vtkSmartPointer<vtkPolyData> Surface;
  vtkNew<vtkPolyDataSilhouette> Silhouette;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkPolyDataMapper> SurfaceMapper;
  vtkNew<vtkActor> SurfaceActor;
  vtkNew<vtkPolyDataMapper> ContourMapper;
  vtkNew<vtkActor> ContourActor;
};

#endif
