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

vtkSmartPointer<vtkImageData> renderSurfaceView(
  const TriangleMesh& mesh, const PinholeCamera& intrinsics, const CameraPose& cameraToCT)
{
  if (mesh.numberOfFaces() == 0)
  {
    throw Error("surface view: the mesh has no faces");
  }
  intrinsics.validate();
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(toPolyData(mesh));
  normals->SplittingOff();
  normals->ConsistencyOff(); // the faces are oriented already: into the air
  normals->ComputePointNormalsOn();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.93, 0.62, 0.55);
  actor->GetProperty()->SetInterpolationToGouraud();
  actor->GetProperty()->SetAmbient(0.08);
  actor->GetProperty()->SetDiffuse(0.9);
  actor->GetProperty()->SetSpecular(0.15);
  actor->GetProperty()->SetSpecularPower(20.0);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.0, 0.0, 0.0);
  renderer->AddActor(actor);
  renderer->AutomaticLightCreationOff();
  // The endoscope's light sits at the lens: near tissue is bright, far tissue dim.
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->PositionalOn();
  light->SetConeAngle(180.0);
  light->SetPosition(cameraToCT.centre.data());
  const Eigen::Vector3d focal = cameraToCT.centre + cameraToCT.viewDirection();
  light->SetFocalPoint(focal.data());
  light->SetAttenuationValues(0.3, 0.0, 0.004);
  renderer->AddLight(light);

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  window->SetSize(intrinsics.widthPx, intrinsics.heightPx);
  setVTKCamera(renderer->GetActiveCamera(), intrinsics, cameraToCT, 0.1, 300.0);
  return captureWindow(window);
}

} // namespace vimlop
