#include <vimlop/Rendering/SurfaceView.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Rendering/VTKCameraAdapter.h>
#include <vimlop/Rendering/WindowCapture.h>

#include <vtkActor.h>
#include <vtkAutoInit.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

VTK_MODULE_INIT(vtkRenderingOpenGL2);

namespace vimlop
{

struct SurfaceView::Internals
{
  vtkNew<vtkPolyDataMapper> mapper;
  vtkNew<vtkActor> actor;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkLight> light;
  vtkNew<vtkRenderWindow> window;
};

SurfaceView::SurfaceView(const TriangleMesh& mesh)
  : Impl(std::make_unique<Internals>())
{
  if (mesh.numberOfFaces() == 0)
  {
    throw Error("surface view: the mesh has no faces");
  }
  Internals& s = *this->Impl;
  // The normals once, into a mesh of the view's own: the mapper uploads it once.
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(toPolyData(mesh));
  normals->SplittingOff();
  normals->ConsistencyOff(); // the faces are oriented already: into the air
  normals->ComputePointNormalsOn();
  normals->Update();
  vtkNew<vtkPolyData> shaded;
  shaded->ShallowCopy(normals->GetOutput());
  s.mapper->SetInputData(shaded);
  s.mapper->ScalarVisibilityOff();
  s.actor->SetMapper(s.mapper);
  s.actor->GetProperty()->SetColor(0.93, 0.62, 0.55);
  s.actor->GetProperty()->SetInterpolationToGouraud();
  s.actor->GetProperty()->SetAmbient(0.08);
  s.actor->GetProperty()->SetDiffuse(0.9);
  s.actor->GetProperty()->SetSpecular(0.15);
  s.actor->GetProperty()->SetSpecularPower(20.0);

  s.renderer->SetBackground(0.0, 0.0, 0.0);
  s.renderer->AddActor(s.actor);
  s.renderer->AutomaticLightCreationOff();
  // The endoscope's light sits at the lens: near tissue is bright, far tissue dim.
  s.light->SetLightTypeToSceneLight();
  s.light->PositionalOn();
  s.light->SetConeAngle(180.0);
  s.light->SetAttenuationValues(0.3, 0.0, 0.004);
  s.renderer->AddLight(s.light);

  s.window->SetOffScreenRendering(1);
  s.window->SetMultiSamples(0);
  s.window->AddRenderer(s.renderer);
}

SurfaceView::~SurfaceView() = default;

vtkSmartPointer<vtkImageData> SurfaceView::render(
  const PinholeCamera& intrinsics, const CameraPose& cameraToCT)
{
  intrinsics.validate();
  Internals& s = *this->Impl;
  s.light->SetPosition(cameraToCT.centre.data());
  const Eigen::Vector3d focal = cameraToCT.centre + cameraToCT.viewDirection();
  s.light->SetFocalPoint(focal.data());
  s.window->SetSize(intrinsics.widthPx, intrinsics.heightPx);
  setVTKCamera(s.renderer->GetActiveCamera(), intrinsics, cameraToCT, 0.1, 300.0);
  return captureWindow(s.window);
}

vtkSmartPointer<vtkImageData> renderSurfaceView(
  const TriangleMesh& mesh, const PinholeCamera& intrinsics, const CameraPose& cameraToCT)
{
  return SurfaceView(mesh).render(intrinsics, cameraToCT);
}

} // namespace vimlop
