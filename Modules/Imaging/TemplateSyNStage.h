#ifndef vimlop_TemplateSyNStage_h
#define vimlop_TemplateSyNStage_h

// Private to the Imaging module (not installed); see TemplateRegistrationITK.h.

#include <vimlop/Imaging/ProgressCallback.h>
#include <vimlop/Imaging/TemplateRegistration.h>
#include <vimlop/Imaging/TemplateRegistrationITK.h>

namespace vimlop::templatereg
{

/**
 * @brief Step 5 of TemplateRegistration::compute(): ITK's greedy symmetric
 * diffeomorphic registration (itk::SyNImageRegistrationMethod),
 * multi-resolution, of the template crop (fixed) to the patient crop
 * (moving), the earlier stages' map composed before it.
 */
struct TemplateSyNStage
{
  /// The deformation on the template crop: a template point x goes to
  /// initial(phi(x)) in the patient. Carries its inverse field too.
  FieldTransform::Pointer phi;
  /// Last value of the metric (ITK's sign: lower is better).
  double metricValue = 0.0;

  /**
   * @brief Registers `fixed`, the clamped template crop `fixedVolume`, to
   * `moving`, the clamped patient crop, after `initial` (the affine map, or
   * the affine map after the B-spline stage). Progress goes from
   * 0.2 to 0.95.
   * @throws vimlop::Error when ITK fails; a transform that left the patient
   * crop is reported with the affine stage's `overlapFraction`.
   */
  static TemplateSyNStage compute(const CTVolume& fixedVolume, const Image* fixed,
    const Image* moving, const InitialTransform* initial, double overlapFraction,
    const TemplateRegistrationOptions& options, const ProgressCallback& progress);
};

} // namespace vimlop::templatereg

#endif
