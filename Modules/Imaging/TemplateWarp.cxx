#include <vimlop/Imaging/TemplateWarp.h>

#include <vimlop/Core/Rotation.h>

#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>

#include <algorithm>

namespace vimlop
{

namespace
{

std::array<double, 3> toArray(const Eigen::Vector3d& v)
{
  return { v[0], v[1], v[2] };
}

Eigen::Vector3d mapped(const DisplacementField& field, const Eigen::Vector3d& p)
{
  const std::array<double, 3> q = field.transformPoint(toArray(p));
  return Eigen::Vector3d(q[0], q[1], q[2]);
}

} // namespace

Eigen::Matrix3d mapJacobian(const DisplacementField& field, const Eigen::Vector3d& pointMm)
{
  const double h = *std::min_element(field.spacingMm.begin(), field.spacingMm.end());
  Eigen::Matrix3d jacobian;
  for (int axis = 0; axis < 3; ++axis)
  {
    const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(axis);
    // Differences across the grid's border would see the clamped extension,
    // not the field: step inwards only there.
    const bool forward = field.contains(toArray(pointMm + step));
    const bool backward = field.contains(toArray(pointMm - step));
    const Eigen::Vector3d a = backward || !forward ? pointMm - step : pointMm;
    const Eigen::Vector3d b = forward || !backward ? pointMm + step : pointMm;
    jacobian.col(axis) = (mapped(field, b) - mapped(field, a)) / (b - a).norm();
  }
  return jacobian;
}

CameraPose warpCameraPose(const CameraPose& pose, const DisplacementField& field)
{
  CameraPose warped;
  warped.centre = mapped(field, pose.centre);
  warped.rotation = nearestRotation(mapJacobian(field, pose.centre)) * pose.rotation;
  return warped;
}

std::vector<FramePose> warpFramePoses(
  const std::vector<FramePose>& poses, const DisplacementField& field)
{
  std::vector<FramePose> warped;
  warped.reserve(poses.size());
  for (const FramePose& pose : poses)
  {
    warped.push_back({ pose.frameId, warpCameraPose(pose.cameraToWorld, field) });
  }
  return warped;
}

vtkSmartPointer<vtkPolyData> warpSurface(vtkPolyData* surface, const DisplacementField& field)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(surface->GetNumberOfPoints());
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    double p[3];
    surface->GetPoint(i, p);
    const std::array<double, 3> q = field.transformPoint({ p[0], p[1], p[2] });
    points->SetPoint(i, q.data());
  }
  vtkNew<vtkPolyData> moved;
  moved->ShallowCopy(surface);
  moved->SetPoints(points);
  // Old normals describe the old geometry.
  moved->GetPointData()->SetNormals(nullptr);
  moved->GetCellData()->SetNormals(nullptr);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(moved);
  // The winding is the orientation: keep it (no re-orientation, no splitting).
  normals->ConsistencyOff();
  normals->AutoOrientNormalsOff();
  normals->SplittingOff();
  normals->ComputePointNormalsOn();
  normals->ComputeCellNormalsOn();
  normals->Update();
  return normals->GetOutput();
}

} // namespace vimlop
