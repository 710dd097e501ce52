#ifndef vimlop_TemplateBSplineStage_h
#define vimlop_TemplateBSplineStage_h

// Private to the Imaging module (not installed); see TemplateRegistrationITK.h.

#include <vimlop/Imaging/ProgressCallback.h>
#include <vimlop/Imaging/TemplateRegistration.h>
#include <vimlop/Imaging/TemplateRegistrationITK.h>

namespace vimlop::templatereg
{

/**
 * @brief Step 4 of TemplateRegistration::compute(), when
 * `bsplineGridMm` is not empty: a cubic B-spline deformation of the template
 * crop (fixed) to the patient crop (moving), after `affine`, its control
 * grid refined level by level: L-BFGS on BSplineMutualInformationCost.
 */
struct TemplateBSplineStage
{
  /// The deformation sampled on the template crop's grid: a template point x
  /// goes to affine(b(x)) in the patient. Carries its inverse field too.
  FieldTransform::Pointer field;
  /// Last value of the cost (negated mutual information plus the weighted
  /// bending energy: lower is better).
  double metricValue = 0.0;

  /**
   * @brief Registers `fixed`, the clamped template crop `fixedVolume`, to
   * `moving` after `affine`.
   * @throws vimlop::Error when ITK fails.
   */
  static TemplateBSplineStage compute(const CTVolume& fixedVolume, const Image* fixed,
    const Image* moving, const AffineTransform* affine, double overlapFraction,
    const TemplateRegistrationOptions& options, const ProgressCallback& progress);
};

} // namespace vimlop::templatereg

#endif
