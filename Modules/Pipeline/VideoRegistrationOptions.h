#ifndef vimlop_VideoRegistrationOptions_h
#define vimlop_VideoRegistrationOptions_h

#include <vimlop/Core/CanonicalPoses.h>
#include <vimlop/Core/MultiStartRegistration.h>
#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Video/ContourDetectionOptions.h>
#include <vimlop/Video/FieldOfViewOptions.h>

namespace vimlop
{

/**
 * @brief Every setting of the main job, with the production defaults:
 * the one set `vimlop register`, the VTK face and Python use. Each scalar
 * setting has a row in RegistrationOptionTable.h (those of `registration`,
 * e.g. its `threads`, which every stage uses) or VideoRegistrationOptionTable.h.
 */
struct VideoRegistrationOptions
{
  /// V2-V12: method, noise, outliers, constraint, convergence. Core's
  /// defaults are the production ones (Σ2d 1 px², κ 200, stall 0.001 %
  /// over 10 iterations, at most 300). minScale and maxScale are set from
  /// `scaleBoundFactor` around the initial scale by registrationOptions().
  RegistrationOptions registration;
  /// V7: scale bounds: the initial scale divided and multiplied by this
  /// (default 1.25, the bound P2 and P3 are measured with; a registration
  /// that ends at it is warned about, its tracker scale may be wrong).
  double scaleBoundFactor = 1.25;
  /// V1: std added to every SfM point's covariance, mm (default 0.1): the
  /// model's own error and what triangulation geometry does not capture.
  double pointNoiseFloorMm = 0.1;
  /// V1: the video contour detector (see OccludingContourDetector).
  ContourDetectionOptions contours;
  /// The field stop: contour points and SfM features outside it (and within
  /// its margin) are not used (default Auto: detected from the frames;
  /// frames without a dark border are used whole, as with None).
  FieldOfViewOptions fieldOfView;
  /// V13 b: the canonical poses generated along the airway when no pose file is given.
  CanonicalPoseOptions canonical;
  /// V13: the multi-start and its failure flag (screening, finalists,
  /// scale factors, contour-error threshold). Its `registration` is
  /// replaced by registrationOptions().
  MultiStartOptions multiStart;

  /**
   * @brief The registration options for a start at `initialScale` (mm
   * per SfM unit): `registration` with the scale bounds of
   * `scaleBoundFactor`.
   */
  RegistrationOptions registrationOptions(double initialScale) const;
  /// @brief Checks every table row against its range, then the nested structs.
  /// @throws vimlop::Error naming the first invalid field.
  void validate() const;
};

} // namespace vimlop

#endif
