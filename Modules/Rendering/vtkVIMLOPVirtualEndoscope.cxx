#include <vimlop/Rendering/vtkVIMLOPVirtualEndoscope.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Rendering/VTKCameraAdapter.h>

#include <vtkActor.h>
#include <vtkAutoInit.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

VTK_MODULE_INIT(vtkRenderingOpenGL2);

vtkStandardNewMacro(vtkVIMLOPVirtualEndoscope);

namespace
{

/// 1-D Gaussian kernel of standard deviation `sigma`, radius 3 sigma (at least 1).
std::vector<double> gaussianKernel(double sigma)
{
  const int radius = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
  std::vector<double> kernel(2 * radius + 1);
  double sum = 0.0;
  for (int i = -radius; i <= radius; ++i)
  {
    kernel[i + radius] = std::exp(-0.5 * i * i / (sigma * sigma));
    sum += kernel[i + radius];
  }
  for (double& k : kernel)
  {
    k /= sum;
  }
  return kernel;
}

/// Separable blur of a w x h x 3 image in place, replicating the border.
void blur(std::vector<double>& image, int w, int h, double sigma)
{
  const std::vector<double> kernel = gaussianKernel(sigma);
  const int radius = static_cast<int>(kernel.size() / 2);
  std::vector<double> tmp(image.size());
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      for (int c = 0; c < 3; ++c)
      {
        double sum = 0.0;
        for (int k = -radius; k <= radius; ++k)
        {
          const int uu = std::clamp(u + k, 0, w - 1);
          sum += kernel[k + radius] * image[3 * (static_cast<size_t>(v) * w + uu) + c];
        }
        tmp[3 * (static_cast<size_t>(v) * w + u) + c] = sum;
      }
    }
  }
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      for (int c = 0; c < 3; ++c)
      {
        double sum = 0.0;
        for (int k = -radius; k <= radius; ++k)
        {
          const int vv = std::clamp(v + k, 0, h - 1);
          sum += kernel[k + radius] * tmp[3 * (static_cast<size_t>(vv) * w + u) + c];
        }
        image[3 * (static_cast<size_t>(v) * w + u) + c] = sum;
      }
    }
  }
}

} // namespace

vtkVIMLOPVirtualEndoscope::vtkVIMLOPVirtualEndoscope()
{
  this->Window->SetOffScreenRendering(1);
  // Anti-aliasing comes from supersampling, which keeps the depth pass exact.
  this->Window->SetMultiSamples(0);
  this->Window->AddRenderer(this->Renderer);
  this->Renderer->SetBackground(0.0, 0.0, 0.0);
  this->Renderer->AutomaticLightCreationOff();
  this->Colours->SetNumberOfComponents(3);
  this->Colours->SetName("Colours");
  this->Mapper->SetInputData(this->Surface);
  this->Mapper->SetScalarModeToUsePointData();
  this->Mapper->SetColorModeToDirectScalars();
  this->Mapper->ScalarVisibilityOn();
  this->Actor->SetMapper(this->Mapper);
  // The light is computed per vertex (see Illuminate), so VTK shows the
  // vertex colours as they are.
  vtkProperty* property = this->Actor->GetProperty();
  property->LightingOff();
  property->SetAmbient(0.0);
  property->SetDiffuse(1.0);
  property->SetSpecular(0.0);
  property->BackfaceCullingOff();
  property->FrontfaceCullingOff();
  property->SetInterpolationToGouraud();
  this->Renderer->AddActor(this->Actor);
}

vtkVIMLOPVirtualEndoscope::~vtkVIMLOPVirtualEndoscope() = default;

void vtkVIMLOPVirtualEndoscope::SetMesh(
  const vimlop::TriangleMesh& mesh, const vimlop::MucosaTexture& texture)
{
  if (mesh.numberOfFaces() == 0)
  {
    throw vimlop::Error("virtual endoscope: the mesh has no faces");
  }
  std::vector<Eigen::Vector3d> positions = mesh.vertices();
  std::vector<Eigen::Vector3d> normals = mesh.vertexNormals();
  std::vector<Eigen::Vector3i> faces = mesh.faces();
  for (int level = 0; level < this->SubdivisionLevels; ++level)
  {
    // Each triangle becomes four through its edge midpoints; the midpoint's
    // shading normal is the mean of the edge's vertex normals, so the surface
    // stays exactly the same and its shading smooth.
    std::map<std::pair<int, int>, int> midpoints;
    auto midpoint = [&](int a, int b)
    {
      const std::pair<int, int> key(std::min(a, b), std::max(a, b));
      const auto found = midpoints.find(key);
      if (found != midpoints.end())
      {
        return found->second;
      }
      const int index = static_cast<int>(positions.size());
      positions.push_back(0.5 * (positions[a] + positions[b]));
      Eigen::Vector3d n = normals[a] + normals[b];
      normals.push_back(n.norm() > 1e-12 ? Eigen::Vector3d(n.normalized()) : normals[a]);
      midpoints.emplace(key, index);
      return index;
    };
    std::vector<Eigen::Vector3i> finer;
    finer.reserve(4 * faces.size());
    for (const Eigen::Vector3i& f : faces)
    {
      const int ab = midpoint(f[0], f[1]);
      const int bc = midpoint(f[1], f[2]);
      const int ca = midpoint(f[2], f[0]);
      finer.emplace_back(f[0], ab, ca);
      finer.emplace_back(ab, f[1], bc);
      finer.emplace_back(ca, bc, f[2]);
      finer.emplace_back(ab, bc, ca);
    }
    faces.swap(finer);
  }

  this->Positions = std::move(positions);
  this->Normals = std::move(normals);
  this->Albedo.resize(this->Positions.size());
  for (size_t i = 0; i < this->Positions.size(); ++i)
  {
    this->Albedo[i] = texture.albedo(this->Positions[i]).cast<float>();
  }

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(this->Positions.size()));
  for (size_t i = 0; i < this->Positions.size(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), this->Positions[i].data());
  }
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(
    static_cast<vtkIdType>(faces.size()), 3 * static_cast<vtkIdType>(faces.size()));
  for (const Eigen::Vector3i& f : faces)
  {
    const vtkIdType ids[3] = { f[0], f[1], f[2] };
    polys->InsertNextCell(3, ids);
  }
  this->Surface->Initialize();
  this->Surface->SetPoints(points);
  this->Surface->SetPolys(polys);
  this->Colours->SetNumberOfTuples(static_cast<vtkIdType>(this->Positions.size()));
  this->Colours->FillValue(0);
  this->Surface->GetPointData()->SetScalars(this->Colours);
  this->Modified();
}

vtkIdType vtkVIMLOPVirtualEndoscope::GetNumberOfRenderedTriangles() const
{
  return this->Surface->GetNumberOfPolys();
}

double vtkVIMLOPVirtualEndoscope::Encode(double radiance) const
{
  const double x = std::max(0.0, radiance) * this->Exposure;
  return 255.0 * std::pow(x / (1.0 + x), 1.0 / 2.2);
}

void vtkVIMLOPVirtualEndoscope::Illuminate(const Eigen::Vector3d& lightCT)
{
  const double r0 = this->ReferenceDistanceMm;
  const double d = this->DiffuseFraction;
  unsigned char* colours = this->Colours->GetPointer(0);
  for (size_t i = 0; i < this->Positions.size(); ++i)
  {
    const Eigen::Vector3d toLight = lightCT - this->Positions[i];
    const double r2 = std::max(toLight.squaredNorm(), 1e-6);
    // The normal points into the air, towards a camera that sees the face.
    const double cosine = std::max(0.0, this->Normals[i].dot(toLight) / std::sqrt(r2));
    const double falloff = r0 * r0 / r2;
    const double diffuse = ((1.0 - d) + d * cosine) * falloff;
    const double specular =
      this->SpecularStrength * std::pow(cosine, this->SpecularPower) * falloff;
    for (int c = 0; c < 3; ++c)
    {
      const double value = this->Encode(this->Albedo[i][c] * diffuse + specular);
      colours[3 * i + c] = static_cast<unsigned char>(std::clamp(std::lround(value), 0L, 255L));
    }
  }
  this->Colours->Modified();
}

vimlop::EndoscopeImage vtkVIMLOPVirtualEndoscope::Render(
  const vimlop::PinholeCamera& k, const vimlop::CameraPose& pose, std::uint64_t noiseSeed)
{
  if (this->Positions.empty())
  {
    throw vimlop::Error("virtual endoscope: no mesh was set");
  }
  k.validate();
  const int w = k.widthPx;
  const int h = k.heightPx;
  const int s = this->Supersampling;
  this->Illuminate(pose.centre);

  // Colour at s times the size: pixel u of the picture covers pixels
  // s u .. s u + s - 1 of the large render, whose centres average to u when
  // c' = s (c + 0.5) - 0.5.
  vimlop::PinholeCamera large = k.resampled(s);
  large.removeDistortion();
  this->Window->SetSize(large.widthPx, large.heightPx);
  vimlop::setVTKCamera(
    this->Renderer->GetActiveCamera(), large, pose, this->NearClipMm, this->FarClipMm);
  this->Window->Render();
  vtkNew<vtkUnsignedCharArray> pixels;
  this->Window->GetPixelData(0, 0, large.widthPx - 1, large.heightPx - 1, 0, pixels, 0);

  std::vector<double> image(static_cast<size_t>(w) * h * 3, 0.0);
  const unsigned char* p = pixels->GetPointer(0);
  const double norm = 1.0 / (s * s);
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      for (int dv = 0; dv < s; ++dv)
      {
        // OpenGL rows run bottom-up.
        const int row = large.heightPx - 1 - (s * v + dv);
        for (int du = 0; du < s; ++du)
        {
          const unsigned char* px = p + 3 * (static_cast<size_t>(row) * large.widthPx + s * u + du);
          for (int c = 0; c < 3; ++c)
          {
            image[3 * (static_cast<size_t>(v) * w + u) + c] += norm * px[c];
          }
        }
      }
    }
  }
  if (this->BlurSigmaPx > 0.0)
  {
    blur(image, w, h, this->BlurSigmaPx);
  }

  vimlop::EndoscopeImage out;
  out.widthPx = w;
  out.heightPx = h;
  out.rgb.resize(image.size());
  std::mt19937_64 rng(noiseSeed * 0x9e3779b97f4a7c15ull + 12345u);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (size_t i = 0; i < image.size(); ++i)
  {
    const double value = image[i] + (this->NoiseSigma > 0.0 ? this->NoiseSigma * noise(rng) : 0.0);
    out.rgb[i] = static_cast<std::uint8_t>(std::clamp(std::lround(value), 0L, 255L));
  }

  // Depth at the picture's own pixel centres.
  this->Window->SetSize(w, h);
  vimlop::setVTKCamera(
    this->Renderer->GetActiveCamera(), k, pose, this->NearClipMm, this->FarClipMm);
  this->Window->Render();
  std::vector<float> z(static_cast<size_t>(w) * h);
  this->Window->GetZbufferData(0, 0, w - 1, h - 1, z.data());
  out.depth.widthPx = w;
  out.depth.heightPx = h;
  out.depth.depthMm.resize(z.size());
  for (int v = 0; v < h; ++v)
  {
    const float* row = z.data() + static_cast<size_t>(h - 1 - v) * w;
    for (int u = 0; u < w; ++u)
    {
      out.depth.depthMm[static_cast<size_t>(v) * w + u] =
        static_cast<float>(vimlop::depthFromZBuffer(row[u], this->NearClipMm, this->FarClipMm));
    }
  }
  return out;
}

void vtkVIMLOPVirtualEndoscope::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SubdivisionLevels: " << this->SubdivisionLevels << "\n";
  os << indent << "ReferenceDistanceMm: " << this->ReferenceDistanceMm << "\n";
  os << indent << "DiffuseFraction: " << this->DiffuseFraction << "\n";
  os << indent << "SpecularStrength: " << this->SpecularStrength << "\n";
  os << indent << "SpecularPower: " << this->SpecularPower << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "Supersampling: " << this->Supersampling << "\n";
  os << indent << "BlurSigmaPx: " << this->BlurSigmaPx << "\n";
  os << indent << "NoiseSigma: " << this->NoiseSigma << "\n";
  os << indent << "NearClipMm: " << this->NearClipMm << "\n";
  os << indent << "FarClipMm: " << this->FarClipMm << "\n";
  os << indent << "Vertices: " << this->Positions.size() << "\n";
}
