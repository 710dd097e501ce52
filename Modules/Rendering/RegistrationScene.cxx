#include <vimlop/Rendering/RegistrationScene.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Rendering/WindowCapture.h>

#include <vtkActor.h>
#include <vtkArrowSource.h>
#include <vtkAutoInit.h>
#include <vtkAxesActor.h>
#include <vtkCamera.h>
#include <vtkCaptionActor2D.h>
#include <vtkCellArray.h>
#include <vtkClipPolyData.h>
#include <vtkDoubleArray.h>
#include <vtkGlyph3D.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPlane.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTextProperty.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

VTK_MODULE_INIT(vtkRenderingOpenGL2);

namespace vimlop
{

namespace
{

/// Arrows along the cameras' viewing directions and a line joining their centres.
void addCameraPath(vtkRenderer* renderer, const std::vector<CameraPose>& cameras, double lengthMm,
  const double colour[3])
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> directions;
  directions->SetName("Direction");
  directions->SetNumberOfComponents(3);
  vtkNew<vtkCellArray> path;
  path->InsertNextCell(static_cast<int>(cameras.size()));
  for (const CameraPose& camera : cameras)
  {
    path->InsertCellPoint(points->InsertNextPoint(camera.centre.data()));
    directions->InsertNextTuple(camera.viewDirection().data());
  }
  vtkNew<vtkPolyData> centres;
  centres->SetPoints(points);
  centres->GetPointData()->SetVectors(directions);
  vtkNew<vtkPolyData> line;
  line->SetPoints(points);
  line->SetLines(path);

  vtkNew<vtkArrowSource> arrow;
  arrow->SetTipResolution(16);
  arrow->SetShaftResolution(16);
  vtkNew<vtkGlyph3D> glyphs;
  glyphs->SetInputData(centres);
  glyphs->SetSourceConnection(arrow->GetOutputPort());
  glyphs->SetVectorModeToUseVector();
  glyphs->SetScaleModeToDataScalingOff();
  glyphs->SetScaleFactor(lengthMm);

  for (int part = 0; part < 2; ++part)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    if (part == 0)
    {
      mapper->SetInputConnection(glyphs->GetOutputPort());
    }
    else
    {
      mapper->SetInputData(line);
    }
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(colour[0], colour[1], colour[2]);
    actor->GetProperty()->SetLineWidth(2.0f);
    renderer->AddActor(actor);
  }
}

/**
 * The CT frame's axes in the bottom left corner, turned with the view: +x
 * "L", +y "P", +z "S" (LPS), so that a reader knows which side of the head
 * they look at. A renderer of its own on a layer above, whose camera looks
 * the main camera's way at the axes from a fixed distance.
 */
void addOrientationMarker(vtkRenderWindow* window, vtkCamera* mainCamera)
{
  vtkNew<vtkAxesActor> axes;
  axes->SetXAxisLabelText("L");
  axes->SetYAxisLabelText("P");
  axes->SetZAxisLabelText("S");
  axes->SetTotalLength(1.0, 1.0, 1.0);
  axes->SetShaftTypeToCylinder();
  axes->SetCylinderRadius(0.04);
  for (vtkCaptionActor2D* caption : { axes->GetXAxisCaptionActor2D(),
         axes->GetYAxisCaptionActor2D(), axes->GetZAxisCaptionActor2D() })
  {
    caption->GetCaptionTextProperty()->SetColor(1.0, 1.0, 1.0);
    caption->GetCaptionTextProperty()->ShadowOff();
    caption->GetCaptionTextProperty()->ItalicOff();
  }
  vtkNew<vtkRenderer> corner;
  corner->SetLayer(1);
  corner->SetViewport(0.0, 0.0, 0.2, 0.2 * window->GetSize()[0] / window->GetSize()[1]);
  corner->InteractiveOff();
  corner->AddActor(axes);
  double direction[3];
  mainCamera->GetDirectionOfProjection(direction);
  vtkCamera* camera = corner->GetActiveCamera();
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetPosition(-4.0 * direction[0], -4.0 * direction[1], -4.0 * direction[2]);
  camera->SetViewUp(mainCamera->GetViewUp());
  camera->SetViewAngle(30.0);
  corner->ResetCameraClippingRange();
  window->SetNumberOfLayers(2);
  window->AddRenderer(corner);
}

} // namespace

vtkSmartPointer<vtkImageData> renderRegistrationScene(const TriangleMesh& model,
  const std::vector<Eigen::Vector3d>& pointsCT, const std::vector<CameraPose>& camerasCT,
  const std::vector<CameraPose>& trueCamerasCT, int widthPx, int heightPx)
{
  if (model.numberOfFaces() == 0)
  {
    throw Error("3-D scene: the model has no faces");
  }
  if (pointsCT.empty() && camerasCT.empty())
  {
    throw Error("3-D scene: no points and no cameras to show");
  }

  // The region of interest: the data and the cameras.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : pointsCT)
  {
    centre += p;
  }
  for (const CameraPose& c : camerasCT)
  {
    centre += c.centre;
  }
  centre /= static_cast<double>(pointsCT.size() + camerasCT.size());
  double radius = 5.0;
  for (const Eigen::Vector3d& p : pointsCT)
  {
    radius = std::max(radius, (p - centre).norm());
  }
  for (const CameraPose& c : camerasCT)
  {
    radius = std::max(radius, (c.centre - centre).norm());
  }

  // Seen from the side of the path: along the cameras' mean x axis.
  Eigen::Vector3d side = Eigen::Vector3d::Zero();
  Eigen::Vector3d up = Eigen::Vector3d::Zero();
  for (const CameraPose& c : camerasCT)
  {
    side += c.rotation.col(0);
    up -= c.rotation.col(1);
  }
  if (side.norm() < 1e-6)
  {
    side = Eigen::Vector3d::UnitX();
  }
  side.normalize();
  up -= up.dot(side) * side;
  if (up.norm() < 1e-6)
  {
    up = side.unitOrthogonal();
  }
  up.normalize();

  vtkNew<vtkPlane> cut;
  cut->SetOrigin(centre.data());
  cut->SetNormal(side.data());
  vtkNew<vtkClipPolyData> clip;
  clip->SetInputData(toPolyData(model));
  clip->SetClipFunction(cut);
  clip->InsideOutOn();               // keep the half beyond the data, away from the viewer
  vtkNew<vtkPolyDataNormals> smooth; // Gouraud shading reads better than facets
  smooth->SetInputConnection(clip->GetOutputPort());
  smooth->SplittingOff();
  smooth->ConsistencyOff();
  vtkNew<vtkPolyDataMapper> modelMapper;
  modelMapper->SetInputConnection(smooth->GetOutputPort());
  modelMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> modelActor;
  modelActor->SetMapper(modelMapper);
  modelActor->GetProperty()->SetColor(0.88, 0.74, 0.68);
  modelActor->GetProperty()->SetSpecular(0.1);

  vtkNew<vtkPoints> points;
  for (const Eigen::Vector3d& p : pointsCT)
  {
    points->InsertNextPoint(p.data());
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<vtkSphereSource> ball;
  ball->SetRadius(0.012 * radius);
  ball->SetThetaResolution(8);
  ball->SetPhiResolution(6);
  vtkNew<vtkGlyph3D> balls;
  balls->SetInputData(cloud);
  balls->SetSourceConnection(ball->GetOutputPort());
  balls->SetScaleModeToDataScalingOff();
  vtkNew<vtkPolyDataMapper> pointMapper;
  pointMapper->SetInputConnection(balls->GetOutputPort());
  pointMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> pointActor;
  pointActor->SetMapper(pointMapper);
  pointActor->GetProperty()->SetColor(0.9, 0.05, 0.05);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.12, 0.12, 0.16);
  renderer->AddActor(modelActor);
  if (!pointsCT.empty())
  {
    renderer->AddActor(pointActor);
  }
  const double arrowMm = 0.25 * radius;
  if (!camerasCT.empty())
  {
    const double yellow[3] = { 1.0, 0.85, 0.1 };
    addCameraPath(renderer, camerasCT, arrowMm, yellow);
  }
  if (!trueCamerasCT.empty())
  {
    const double cyan[3] = { 0.1, 0.85, 0.95 };
    addCameraPath(renderer, trueCamerasCT, arrowMm, cyan);
  }

  vtkCamera* camera = renderer->GetActiveCamera();
  const double viewAngleDeg = 30.0;
  const double distance = 1.15 * radius / std::sin(0.5 * viewAngleDeg * M_PI / 180.0);
  const Eigen::Vector3d eye = centre + distance * side;
  camera->SetViewAngle(viewAngleDeg);
  camera->SetFocalPoint(centre.data());
  camera->SetPosition(eye.data());
  camera->SetViewUp(up.data());
  camera->SetClippingRange(0.05 * distance, distance + 10.0 * radius);

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  window->SetSize(widthPx, heightPx);
  addOrientationMarker(window, camera);
  return captureWindow(window);
}

} // namespace vimlop
