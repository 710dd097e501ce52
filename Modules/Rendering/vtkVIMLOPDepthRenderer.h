#ifndef vtkVIMLOPDepthRenderer_h
#define vtkVIMLOPDepthRenderer_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/DepthMap.h>
#include <vimlop/Core/PinholeCamera.h>

#include "VIMLOPRenderingModule.h"

#include <vtkNew.h>
#include <vtkObject.h>

class vtkActor;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderer;
class vtkRenderWindow;

/**
 * @brief Renders a surface offscreen from a pinhole camera and reads the
 * z-buffer back as metric depth.
 *
 * Both sides of every face are drawn, so the walls of a cavity are seen from
 * inside. Depth is the camera z (mm) of the nearest surface per pixel centre
 * (see vimlop::DepthMap). Needs an X display (use `xvfb-run -a` on servers).
 */
class VIMLOPRENDERING_EXPORT vtkVIMLOPDepthRenderer : public vtkObject
{
public:
  static vtkVIMLOPDepthRenderer* New();
  vtkTypeMacro(vtkVIMLOPDepthRenderer, vtkObject)
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Surface to render, in the world frame of the camera poses (CT, mm).
  void SetSurface(vtkPolyData* surface);

  ///@{
  /// Near clipping distance along the optical axis. Default 0.5 mm; a smaller
  /// value costs z-buffer precision far away.
  vtkSetClampMacro(NearClipMm, double, 1e-4, 1e6);
  vtkGetMacro(NearClipMm, double);
  ///@}

  ///@{
  /// Far clipping distance along the optical axis. Default 500 mm.
  vtkSetClampMacro(FarClipMm, double, 1e-3, 1e9);
  vtkGetMacro(FarClipMm, double);
  ///@}

  /**
   * @brief Renders the surface as seen by `intrinsics` at `cameraToWorld`
   * and returns the depth of every pixel (image size from the intrinsics).
   * @throws vimlop::Error without a surface or with invalid intrinsics.
   */
  vimlop::DepthMap RenderDepth(
    const vimlop::PinholeCamera& intrinsics, const vimlop::CameraPose& cameraToWorld);

  /// The offscreen window (for colour read-back or custom props).
  vtkRenderWindow* GetRenderWindow();

protected:
  vtkVIMLOPDepthRenderer();
  ~vtkVIMLOPDepthRenderer() override;

private:
  vtkVIMLOPDepthRenderer(const vtkVIMLOPDepthRenderer&) = delete;
  void operator=(const vtkVIMLOPDepthRenderer&) = delete;

  double NearClipMm = 0.5;
  double FarClipMm = 500.0;
  bool HasSurface = false;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkActor> Actor;
};

#endif
