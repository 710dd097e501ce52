#ifndef vtkVIMLOPDepthVisibility_h
#define vtkVIMLOPDepthVisibility_h

#include <vimlop/Core/ContourVisibility.h>
#include <vimlop/Core/TriangleMesh.h>

#include "VIMLOPRenderingModule.h"

#include <vtkNew.h>
#include <vtkObject.h>

#include <memory>

class vtkPolyData;
class vtkVIMLOPDepthRenderer;

/**
 * @brief The paper's contour visibility (V4): the model is rendered offscreen
 * from each camera with its intrinsics, the z-buffer is read back as metric
 * depth, and each contour sample is tested against it.
 *
 * It implements vimlop::ContourVisibility, the interface of the Embree
 * backend, so a vimlop::RegistrationModel can use either (see
 * AsContourVisibility()).
 *
 * The image is rendered at Supersampling times the camera's resolution. A
 * sample at camera depth z that projects to sub-pixel position p is visible when
 * - z <= D(p) + t, with D(p) the depth at the pixel centre nearest to p and
 *   t = max(ToleranceMm, RelativeTolerance z): nothing is in front of it; or
 * - z <= max D(q) + t over the four pixel centres q around p, and
 *   z <= D(p) (1 + SilhouetteTolerance): it is on a silhouette.
 * Why the second rule: contour samples lie on silhouettes, where the face
 * beside them grazes the viewing rays, so the depth at the nearest pixel
 * centre can be a little in front of the sample although nothing hides it;
 * but a visible silhouette has the farther, occluded side next to it. The
 * bound on how far in front D(p) may be keeps samples that something else
 * hides just behind its own outline hidden. Measured against Embree's exact
 * ray tests on the Cranium airway (see the tests), the rules and defaults
 * agree on 98.6 % of contour samples; the disagreements are samples within a
 * fraction of a pixel of an occluder's outline or hidden by surfaces a
 * fraction of a millimetre in front of them, which a z-buffer cannot resolve.
 * Points behind the near plane or outside the image are not visible.
 *
 * Rendering needs an OpenGL context, which belongs to one thread at a time:
 * isThreadSafe() is false and the registration then visits its frames in
 * turn on the calling thread. Needs an X display (`xvfb-run -a` on servers).
 */
class VIMLOPRENDERING_EXPORT vtkVIMLOPDepthVisibility
  : public vtkObject
  , public vimlop::ContourVisibility
{
public:
  static vtkVIMLOPDepthVisibility* New();
  vtkTypeMacro(vtkVIMLOPDepthVisibility, vtkObject)
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * @brief The model to render: the registration model's mesh (CT frame, mm).
   * @throws vimlop::Error for a mesh without faces.
   */
  void SetMesh(const vimlop::TriangleMesh& mesh);

  ///@{
  /// Rendering resolution per axis, in multiples of the camera's (default 3):
  /// finer pixels narrow the band around outlines where the z-buffer cannot
  /// tell (agreement with Embree on the Cranium airway: 98.2 % at 2, 98.6 % at 3).
  vtkSetClampMacro(Supersampling, int, 1, 4);
  vtkGetMacro(Supersampling, int);
  ///@}

  ///@{
  /// Absolute depth tolerance, mm along the optical axis (default 0.01).
  vtkSetClampMacro(ToleranceMm, double, 0.0, 1e3);
  vtkGetMacro(ToleranceMm, double);
  ///@}

  ///@{
  /// Depth tolerance relative to the sample's depth, dimensionless (default
  /// 0.002): covers the z-buffer's quantisation.
  vtkSetClampMacro(RelativeTolerance, double, 0.0, 1.0);
  vtkGetMacro(RelativeTolerance, double);
  ///@}

  ///@{
  /// How far in front of a silhouette sample the surface at its own pixel may
  /// be, relative to the sample's depth (default 0.05). The faces beside a
  /// contour edge of a coarse mesh graze the rays at a few degrees, so their
  /// depth half a pixel away can be several percent in front.
  vtkSetClampMacro(SilhouetteTolerance, double, 0.0, 1.0);
  vtkGetMacro(SilhouetteTolerance, double);
  ///@}

  ///@{
  /// Near and far clipping distances of the rendering, mm along the optical
  /// axis (defaults 0.1 and 300). Samples nearer than the near plane are not
  /// visible (Core drops contour samples nearer than 0.1 mm anyway); a far
  /// plane much beyond the model only costs depth precision.
  void SetNearClipMm(double nearMm);
  double GetNearClipMm() const;
  void SetFarClipMm(double farMm);
  double GetFarClipMm() const;
  ///@}

  /// @brief Sets `visible[i]` (see the class description); renders once per call.
  void classify(const vimlop::PinholeCamera& intrinsics, const vimlop::CameraPose& cameraToCT,
    const std::vector<Eigen::Vector3d>& pointsCT, std::vector<char>& visible) const override;

  /// @brief False: an OpenGL context serves one thread at a time.
  bool isThreadSafe() const override { return false; }

  /**
   * @brief This object as the backend of a vimlop::RegistrationModel
   * (RegistrationModel::setVisibility). The shared pointer holds a VTK
   * reference, so the object lives as long as the model uses it.
   */
  std::shared_ptr<const vimlop::ContourVisibility> AsContourVisibility();

protected:
  vtkVIMLOPDepthVisibility();
  ~vtkVIMLOPDepthVisibility() override;

private:
  vtkVIMLOPDepthVisibility(const vtkVIMLOPDepthVisibility&) = delete;
  void operator=(const vtkVIMLOPDepthVisibility&) = delete;

  int Supersampling = 3;
  double SilhouetteTolerance = 0.05;
  double ToleranceMm = 0.01;
  double RelativeTolerance = 0.002;
  bool HasMesh = false;
  vtkNew<vtkVIMLOPDepthRenderer> Renderer;
};

#endif
