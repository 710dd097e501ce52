#ifndef vtkVIMLOPVirtualEndoscope_h
#define vtkVIMLOPVirtualEndoscope_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Rendering/EndoscopeImage.h>
#include <vimlop/Rendering/MucosaTexture.h>

#include "VIMLOPRenderingModule.h"

#include <vtkNew.h>
#include <vtkObject.h>

#include <cstdint>
#include <vector>

class vtkActor;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderer;
class vtkRenderWindow;
class vtkUnsignedCharArray;

/**
 * @brief A virtual endoscope: renders the airway surface offscreen as an
 * endoscope sees it, with a mucosa-like texture lit by a point light at the
 * optical centre, and reads back the colour picture and the depth map of the
 * same pinhole camera.
 *
 * The surface is subdivided (each level splits every triangle in four, which
 * keeps the geometry exactly) and the procedural MucosaTexture is evaluated at
 * the new vertices, so texture detail is finer than the CT's triangles. For
 * every frame the light is computed per vertex: radiance =
 * albedo x ((1 - d) + d cos θ) x (r0 / r)² + specular x cos^p θ x (r0 / r)²,
 * with r the distance to the light (at the optical centre), θ the angle of
 * incidence, d the DiffuseFraction and r0 the ReferenceDistanceMm. The part
 * 1 - d that does not depend on the incidence stands for the sub-surface
 * scattering of wet mucosa: with a pure Lambertian term every fold would go
 * black at its own silhouette, whereas in endoscopy the nearer tissue is
 * the brighter side of an occluding contour (DESIGN §4). The light is
 * computed here rather than by a positional vtkLight, whose attenuation acts
 * on the diffuse and specular terms only and cannot make the
 * incidence-independent part fall off with distance. Radiance is tone
 * mapped (x E / (1 + x E), E the Exposure) and gamma encoded (1/2.2); the
 * picture is rendered at Supersampling times the size and averaged down, then
 * blurred (BlurSigmaPx) and given Gaussian noise (NoiseSigma).
 *
 * Needs an X display (VTK 9.1 here is built for X11; `xvfb-run -a` on servers).
 */
class VIMLOPRENDERING_EXPORT vtkVIMLOPVirtualEndoscope : public vtkObject
{
public:
  static vtkVIMLOPVirtualEndoscope* New();
  vtkTypeMacro(vtkVIMLOPVirtualEndoscope, vtkObject)
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * @brief The airway surface (CT frame, mm, normals into the air) and its
   * texture; subdivides the surface and evaluates the texture at every vertex.
   * Call again after changing SubdivisionLevels.
   * @throws vimlop::Error for a mesh without faces.
   */
  void SetMesh(const vimlop::TriangleMesh& mesh,
    const vimlop::MucosaTexture& texture = vimlop::MucosaTexture());

  ///@{
  /// Subdivision levels applied by SetMesh (default 2: triangles a sixteenth of the CT mesh's).
  vtkSetClampMacro(SubdivisionLevels, int, 0, 4);
  vtkGetMacro(SubdivisionLevels, int);
  ///@}

  ///@{
  /// Distance at which a surface facing the light has radiance equal to its
  /// albedo, mm (default 6).
  vtkSetClampMacro(ReferenceDistanceMm, double, 1e-3, 1e6);
  vtkGetMacro(ReferenceDistanceMm, double);
  ///@}

  ///@{
  /// Lambertian fraction d of the diffuse light, in [0, 1] (default 0.25).
  vtkSetClampMacro(DiffuseFraction, double, 0.0, 1.0);
  vtkGetMacro(DiffuseFraction, double);
  ///@}

  ///@{
  /// Strength (default 0.25, 0 for none) and Phong exponent (default 40) of
  /// the specular highlights of wet mucosa.
  vtkSetClampMacro(SpecularStrength, double, 0.0, 100.0);
  vtkGetMacro(SpecularStrength, double);
  vtkSetClampMacro(SpecularPower, double, 1.0, 1e4);
  vtkGetMacro(SpecularPower, double);
  ///@}

  ///@{
  /// Exposure E of the tone mapping (default 0.7).
  vtkSetClampMacro(Exposure, double, 1e-6, 1e6);
  vtkGetMacro(Exposure, double);
  ///@}

  ///@{
  /// Render size factor per axis for anti-aliasing (default 2; 1 for none).
  vtkSetClampMacro(Supersampling, int, 1, 4);
  vtkGetMacro(Supersampling, int);
  ///@}

  ///@{
  /// Standard deviation of the Gaussian blur of the picture, pixels (default 0.5; 0 for none).
  vtkSetClampMacro(BlurSigmaPx, double, 0.0, 50.0);
  vtkGetMacro(BlurSigmaPx, double);
  ///@}

  ///@{
  /// Standard deviation of the additive Gaussian noise, grey levels of 255 (default 1.5; 0 for
  /// none).
  vtkSetClampMacro(NoiseSigma, double, 0.0, 255.0);
  vtkGetMacro(NoiseSigma, double);
  ///@}

  ///@{
  /// Near and far clipping distances along the optical axis, mm (defaults 0.2 and 500).
  vtkSetClampMacro(NearClipMm, double, 1e-4, 1e6);
  vtkGetMacro(NearClipMm, double);
  vtkSetClampMacro(FarClipMm, double, 1e-3, 1e9);
  vtkGetMacro(FarClipMm, double);
  ///@}

  /**
   * @brief Renders what `intrinsics` at `cameraToCT` see: the picture and its
   * depth map (image size from the intrinsics). `noiseSeed` makes the noise
   * reproducible (use e.g. the frame index).
   * @throws vimlop::Error without a mesh or with invalid intrinsics.
   */
  vimlop::EndoscopeImage Render(const vimlop::PinholeCamera& intrinsics,
    const vimlop::CameraPose& cameraToCT, std::uint64_t noiseSeed = 0);

  /// @brief Number of triangles rendered (after subdivision).
  vtkIdType GetNumberOfRenderedTriangles() const;

protected:
  vtkVIMLOPVirtualEndoscope();
  ~vtkVIMLOPVirtualEndoscope() override;

private:
  vtkVIMLOPVirtualEndoscope(const vtkVIMLOPVirtualEndoscope&) = delete;
  void operator=(const vtkVIMLOPVirtualEndoscope&) = delete;

  /// Per-vertex colours for a light at `lightCT`.
  void Illuminate(const Eigen::Vector3d& lightCT);
  /// Linear RGB radiance to an 8-bit value (tone map and gamma).
  double Encode(double radiance) const;

  int SubdivisionLevels = 2;
  double ReferenceDistanceMm = 6.0;
  double DiffuseFraction = 0.25;
  double SpecularStrength = 0.25;
  double SpecularPower = 40.0;
  double Exposure = 0.7;
  int Supersampling = 2;
  double BlurSigmaPx = 0.5;
  double NoiseSigma = 1.5;
  double NearClipMm = 0.2;
  double FarClipMm = 500.0;

  std::vector<Eigen::Vector3d> Positions;
  std::vector<Eigen::Vector3d> Normals;
  std::vector<Eigen::Vector3f> Albedo;
  vtkNew<vtkPolyData> Surface;
  vtkNew<vtkUnsignedCharArray> Colours;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkActor> Actor;
};

#endif
