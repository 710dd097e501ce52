#include <vimlop/Rendering/VTKCameraAdapter.h>

#include <vtkCamera.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>

#include <limits>

namespace vimlop
{

void setVTKCamera(
  vtkCamera* camera, const PinholeCamera& k, const CameraPose& pose, double nearMm, double farMm)
{
  // View: VTK looks down -z with y up; OpenCV looks down +z with y down.
  const Eigen::Vector3d focal = pose.centre + pose.viewDirection();
  const Eigen::Vector3d up = -pose.rotation.col(1);
  camera->SetPosition(pose.centre.data());
  camera->SetFocalPoint(focal.data());
  camera->SetViewUp(up.data());
  camera->SetClippingRange(nearMm, farMm);

  // Projection from intrinsics. For a view point (X, Y, Z) (VTK camera frame,
  // Z < 0 in front) and the OpenCV pixel u = fx X / -Z + cx (centre of pixel 0
  // at 0), normalised device x = 2 (u + 0.5) / w - 1; likewise for y, whose
  // rows run bottom-up in OpenGL.
  const double w = k.widthPx;
  const double h = k.heightPx;
  vtkNew<vtkMatrix4x4> projection;
  projection->Zero();
  projection->SetElement(0, 0, 2.0 * k.fx / w);
  projection->SetElement(0, 2, 1.0 - 2.0 * (k.cx + 0.5) / w);
  projection->SetElement(1, 1, 2.0 * k.fy / h);
  projection->SetElement(1, 2, 2.0 * (k.cy + 0.5) / h - 1.0);
  projection->SetElement(2, 2, -(farMm + nearMm) / (farMm - nearMm));
  projection->SetElement(2, 3, -2.0 * farMm * nearMm / (farMm - nearMm));
  projection->SetElement(3, 2, -1.0);
  camera->SetExplicitProjectionTransformMatrix(projection);
  camera->UseExplicitProjectionTransformMatrixOn();
}

double depthFromZBuffer(float zBuffer, double nearMm, double farMm)
{
  if (zBuffer >= 1.0f)
  {
    return std::numeric_limits<double>::infinity();
  }
  const double ndc = 2.0 * zBuffer - 1.0;
  return 2.0 * farMm * nearMm / ((farMm + nearMm) - ndc * (farMm - nearMm));
}

} // namespace vimlop
