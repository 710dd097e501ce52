#include <vimlop/Rendering/vtkVIMLOPSilhouetteRenderer.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Rendering/VTKCameraAdapter.h>

#include <vtkActor.h>
#include <vtkAutoInit.h>
#include <vtkImageData.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataSilhouette.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

VTK_MODULE_INIT(vtkRenderingOpenGL2);

vtkStandardNewMacro(vtkVIMLOPSilhouetteRenderer);

namespace
{

/// VTK's polygon offset is switched on for all mappers at once (a static
/// setting, off by default in this VTK); this turns it on for one render and
/// restores what was there.
class PolygonOffsetDuringRender
{
public:
  PolygonOffsetDuringRender()
    : Previous(vtkMapper::GetResolveCoincidentTopology())
  {
    vtkMapper::SetResolveCoincidentTopologyToPolygonOffset();
  }
  ~PolygonOffsetDuringRender() { vtkMapper::SetResolveCoincidentTopology(this->Previous); }
  PolygonOffsetDuringRender(const PolygonOffsetDuringRender&) = delete;
  PolygonOffsetDuringRender& operator=(const PolygonOffsetDuringRender&) = delete;

private:
  int Previous;
};

} // namespace

vtkVIMLOPSilhouetteRenderer::vtkVIMLOPSilhouetteRenderer()
{
  this->Window->SetOffScreenRendering(1);
  this->Window->SetMultiSamples(0); // a pixel is on the contour or not
  this->Window->AddRenderer(this->Renderer);
  this->Renderer->SetBackground(0.0, 0.0, 0.0);

  // The surface only hides: drawn in the background colour, unlit, and pushed
  // back so that the contour lines on its own edges stay in front of it. The
  // offset (factor 3, units 10) was tuned on the Cranium airway: less hides
  // parts of visible contours behind the grazing faces beside them, more
  // lets contours shine through surfaces just in front of them.
  this->SurfaceMapper->ScalarVisibilityOff();
  this->SurfaceMapper->SetRelativeCoincidentTopologyPolygonOffsetParameters(3.0, 10.0);
  this->SurfaceActor->SetMapper(this->SurfaceMapper);
  this->SurfaceActor->GetProperty()->SetColor(0.0, 0.0, 0.0);
  this->SurfaceActor->GetProperty()->LightingOff();
  this->SurfaceActor->GetProperty()->BackfaceCullingOff();
  this->Renderer->AddActor(this->SurfaceActor);

  this->Silhouette->SetDirectionToSpecifiedOrigin();
  this->Silhouette->SetEnableFeatureAngle(0); // occluding contours only, no creases
  this->Silhouette->BorderEdgesOff();
  this->ContourMapper->SetInputConnection(this->Silhouette->GetOutputPort());
  this->ContourMapper->ScalarVisibilityOff();
  this->ContourActor->SetMapper(this->ContourMapper);
  this->ContourActor->GetProperty()->SetColor(1.0, 1.0, 1.0);
  this->ContourActor->GetProperty()->LightingOff();
  this->Renderer->AddActor(this->ContourActor);
}

vtkVIMLOPSilhouetteRenderer::~vtkVIMLOPSilhouetteRenderer() = default;

void vtkVIMLOPSilhouetteRenderer::SetMesh(const vimlop::TriangleMesh& mesh)
{
  if (mesh.numberOfFaces() == 0)
  {
    throw vimlop::Error("silhouette rendering: the mesh has no faces");
  }
  this->Surface = vimlop::toPolyData(mesh);
  this->SurfaceMapper->SetInputData(this->Surface);
  this->Silhouette->SetInputData(this->Surface);
  this->HasMesh = true;
  this->Modified();
}

vtkPolyData* vtkVIMLOPSilhouetteRenderer::GetContourEdges()
{
  return this->Silhouette->GetOutput();
}

vtkSmartPointer<vtkImageData> vtkVIMLOPSilhouetteRenderer::RenderContours(
  const vimlop::PinholeCamera& intrinsics, const vimlop::CameraPose& cameraToCT)
{
  if (!this->HasMesh)
  {
    throw vimlop::Error("silhouette rendering: no mesh was set");
  }
  intrinsics.validate();
  const int w = intrinsics.widthPx;
  const int h = intrinsics.heightPx;
  this->Silhouette->SetOrigin(cameraToCT.centre.data());
  this->Silhouette->Update();
  this->ContourActor->GetProperty()->SetLineWidth(static_cast<float>(this->LineWidthPx));
  this->Window->SetSize(w, h);
  vimlop::setVTKCamera(
    this->Renderer->GetActiveCamera(), intrinsics, cameraToCT, this->NearClipMm, this->FarClipMm);
  {
    const PolygonOffsetDuringRender offset;
    this->Window->Render();
  }

  vtkNew<vtkUnsignedCharArray> rgb;
  this->Window->GetPixelData(0, 0, w - 1, h - 1, 0, rgb);
  auto mask = vtkSmartPointer<vtkImageData>::New();
  mask->SetDimensions(w, h, 1);
  mask->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* out = static_cast<unsigned char*>(mask->GetScalarPointer());
  // Both buffers run bottom-up, as VTK images do.
  const auto n = static_cast<vtkIdType>(w) * h;
  for (vtkIdType i = 0; i < n; ++i)
  {
    out[i] = rgb->GetValue(3 * i) > 127 ? 255 : 0;
  }
  return mask;
}

void vtkVIMLOPSilhouetteRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NearClipMm: " << this->NearClipMm << "\n";
  os << indent << "FarClipMm: " << this->FarClipMm << "\n";
  os << indent << "LineWidthPx: " << this->LineWidthPx << "\n";
  os << indent << "HasMesh: " << (this->HasMesh ? "yes" : "no") << "\n";
}
