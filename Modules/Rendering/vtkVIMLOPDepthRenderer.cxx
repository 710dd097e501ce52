#include <vimlop/Rendering/vtkVIMLOPDepthRenderer.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Rendering/VTKCameraAdapter.h>

#include <vtkActor.h>
#include <vtkAutoInit.h>
#include <vtkCamera.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

// The OpenGL implementation of vtkRenderWindow registers itself through this
// initialiser; doing it here spares every program that uses us from doing it.
VTK_MODULE_INIT(vtkRenderingOpenGL2);

vtkStandardNewMacro(vtkVIMLOPDepthRenderer);

vtkVIMLOPDepthRenderer::vtkVIMLOPDepthRenderer()
{
  this->Window->SetOffScreenRendering(1);
  this->Window->SetMultiSamples(0); // resolved samples would blend depths at edges
  this->Window->AddRenderer(this->Renderer);
  this->Renderer->SetBackground(0.0, 0.0, 0.0);
  this->Mapper->ScalarVisibilityOff();
  this->Actor->SetMapper(this->Mapper);
  this->Actor->GetProperty()->BackfaceCullingOff();
  this->Actor->GetProperty()->FrontfaceCullingOff();
  this->Renderer->AddActor(this->Actor);
}

vtkVIMLOPDepthRenderer::~vtkVIMLOPDepthRenderer() = default;

void vtkVIMLOPDepthRenderer::SetSurface(vtkPolyData* surface)
{
  this->Mapper->SetInputData(surface);
  this->HasSurface = surface != nullptr;
  this->Modified();
}

vtkRenderWindow* vtkVIMLOPDepthRenderer::GetRenderWindow()
{
  return this->Window;
}

vimlop::DepthMap vtkVIMLOPDepthRenderer::RenderDepth(
  const vimlop::PinholeCamera& intrinsics, const vimlop::CameraPose& cameraToWorld)
{
  if (!this->HasSurface)
  {
    throw vimlop::Error("depth rendering: no surface was set");
  }
  intrinsics.validate();
  const int w = intrinsics.widthPx;
  const int h = intrinsics.heightPx;
  this->Window->SetSize(w, h);
  vimlop::setVTKCamera(this->Renderer->GetActiveCamera(), intrinsics, cameraToWorld,
    this->NearClipMm, this->FarClipMm);
  this->Window->Render();

  std::vector<float> z(static_cast<size_t>(w) * h);
  this->Window->GetZbufferData(0, 0, w - 1, h - 1, z.data());
  vimlop::DepthMap depth;
  depth.widthPx = w;
  depth.heightPx = h;
  depth.depthMm.resize(z.size());
  for (int v = 0; v < h; ++v)
  {
    // OpenGL rows run bottom-up; DepthMap rows run top-down.
    const float* row = z.data() + static_cast<size_t>(h - 1 - v) * w;
    for (int u = 0; u < w; ++u)
    {
      depth.depthMm[static_cast<size_t>(v) * w + u] =
        static_cast<float>(vimlop::depthFromZBuffer(row[u], this->NearClipMm, this->FarClipMm));
    }
  }
  return depth;
}

void vtkVIMLOPDepthRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NearClipMm: " << this->NearClipMm << "\n";
  os << indent << "FarClipMm: " << this->FarClipMm << "\n";
  os << indent << "HasSurface: " << (this->HasSurface ? "yes" : "no") << "\n";
}
