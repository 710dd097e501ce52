#include <vimlop/Rendering/vtkVIMLOPDepthVisibility.h>

#include <vimlop/Core/DepthMap.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Rendering/vtkVIMLOPDepthRenderer.h>

#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkVIMLOPDepthVisibility);

vtkVIMLOPDepthVisibility::vtkVIMLOPDepthVisibility()
{
  this->Renderer->SetNearClipMm(0.1);
  this->Renderer->SetFarClipMm(300.0);
}

vtkVIMLOPDepthVisibility::~vtkVIMLOPDepthVisibility() = default;

void vtkVIMLOPDepthVisibility::SetMesh(const vimlop::TriangleMesh& mesh)
{
  if (mesh.numberOfFaces() == 0)
  {
    throw vimlop::Error("depth visibility: the mesh has no faces");
  }
  this->Renderer->SetSurface(vimlop::toPolyData(mesh));
  this->HasMesh = true;
  this->Modified();
}

void vtkVIMLOPDepthVisibility::SetNearClipMm(double nearMm)
{
  this->Renderer->SetNearClipMm(nearMm);
  this->Modified();
}

double vtkVIMLOPDepthVisibility::GetNearClipMm() const
{
  return this->Renderer->GetNearClipMm();
}

void vtkVIMLOPDepthVisibility::SetFarClipMm(double farMm)
{
  this->Renderer->SetFarClipMm(farMm);
  this->Modified();
}

double vtkVIMLOPDepthVisibility::GetFarClipMm() const
{
  return this->Renderer->GetFarClipMm();
}

void vtkVIMLOPDepthVisibility::classify(const vimlop::PinholeCamera& intrinsics,
  const vimlop::CameraPose& cameraToCT, const std::vector<Eigen::Vector3d>& pointsCT,
  std::vector<char>& visible) const
{
  visible.assign(pointsCT.size(), 0);
  if (pointsCT.empty())
  {
    return;
  }
  if (!this->HasMesh)
  {
    throw vimlop::Error("depth visibility: no mesh was set");
  }
  // Supersampled pixel centres: pixel u of the camera covers [u - 0.5, u + 0.5],
  // i.e. s pixels of the rendering. A margin of one pixel gives samples at the
  // border all four neighbours.
  const int s = this->Supersampling;
  vimlop::PinholeCamera fine = intrinsics.resampled(s);
  fine.cx += 1.0;
  fine.cy += 1.0;
  fine.widthPx += 2;
  fine.heightPx += 2;
  const vimlop::DepthMap depth = this->Renderer->RenderDepth(fine, cameraToCT);
  const double nearMm = this->Renderer->GetNearClipMm();

  for (size_t i = 0; i < pointsCT.size(); ++i)
  {
    const Eigen::Vector3d p = cameraToCT.worldToCamera(pointsCT[i]);
    if (!(p.z() > nearMm))
    {
      continue;
    }
    const Eigen::Vector2d pixel = fine.project(p);
    const double u0 = std::floor(pixel.x());
    const double v0 = std::floor(pixel.y());
    if (!(u0 >= 0.0 && v0 >= 0.0 && u0 + 1.0 < depth.widthPx && v0 + 1.0 < depth.heightPx))
    {
      continue;
    }
    const int u = static_cast<int>(u0);
    const int v = static_cast<int>(v0);
    const double own =
      depth.at(static_cast<int>(std::lround(pixel.x())), static_cast<int>(std::lround(pixel.y())));
    const double farthest = std::max(std::max(depth.at(u, v), depth.at(u + 1, v)),
      std::max(depth.at(u, v + 1), depth.at(u + 1, v + 1)));
    const double z = p.z();
    const double tolerance = std::max(this->ToleranceMm, this->RelativeTolerance * z);
    const bool unoccluded = z <= own + tolerance;
    const bool onSilhouette =
      z <= farthest + tolerance && z <= own * (1.0 + this->SilhouetteTolerance);
    visible[i] = unoccluded || onSilhouette ? 1 : 0;
  }
}

std::shared_ptr<const vimlop::ContourVisibility> vtkVIMLOPDepthVisibility::AsContourVisibility()
{
  // The deleter gives back the reference taken here; VTK frees the object
  // when its last reference goes.
  this->Register(nullptr);
  return std::shared_ptr<const vimlop::ContourVisibility>(this,
    [](const vimlop::ContourVisibility* visibility)
    {
      const_cast<vtkVIMLOPDepthVisibility*>(
        static_cast<const vtkVIMLOPDepthVisibility*>(visibility))
        ->UnRegister(nullptr);
    });
}

void vtkVIMLOPDepthVisibility::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Supersampling: " << this->Supersampling << "\n";
  os << indent << "SilhouetteTolerance: " << this->SilhouetteTolerance << "\n";
  os << indent << "ToleranceMm: " << this->ToleranceMm << "\n";
  os << indent << "RelativeTolerance: " << this->RelativeTolerance << "\n";
  os << indent << "NearClipMm: " << this->GetNearClipMm() << "\n";
  os << indent << "FarClipMm: " << this->GetFarClipMm() << "\n";
  os << indent << "HasMesh: " << (this->HasMesh ? "yes" : "no") << "\n";
}
