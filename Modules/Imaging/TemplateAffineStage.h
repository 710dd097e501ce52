#ifndef vimlop_TemplateAffineStage_h
#define vimlop_TemplateAffineStage_h

// Private to the Imaging module (not installed); see TemplateRegistrationITK.h.

#include <vimlop/Imaging/ProgressCallback.h>
#include <vimlop/Imaging/TemplateRegistration.h>
#include <vimlop/Imaging/TemplateRegistrationITK.h>

namespace vimlop::templatereg
{

/**
 * @brief Step 2 of TemplateRegistration::compute(): the translation that
 * aligns the centroids of the two heads (voxels above -500 HU) starts a
 * multi-resolution affine registration of the template crop (fixed) to the
 * patient (moving), Mattes mutual information, regular step gradient descent
 * with physical-shift parameter scales.
 */
struct TemplateAffineStage
{
  /// Template to patient, about the centre of the template crop.
  AffineTransform::Pointer transform;
  /// Correlation of the intensities with the centroids aligned, before the registration.
  double initialCorrelation = 0.0;
  /// Last value of the metric (ITK's sign: lower is better).
  double metricValue = 0.0;

  /**
   * @brief Registers `fixed`, the clamped template crop `fixedVolume`, to
   * `moving`, the clamped `patientCT`. Progress goes from 0.01 to 0.2.
   * @throws vimlop::Error when ITK fails, naming the overlap when the
   * transform has left the patient CT.
   */
  static TemplateAffineStage compute(const CTVolume& templateCT, const CTVolume& patientCT,
    const CTVolume& fixedVolume, const Image* fixed, const Image* moving,
    const TemplateRegistrationOptions& options, const ProgressCallback& progress);
};

} // namespace vimlop::templatereg

#endif
