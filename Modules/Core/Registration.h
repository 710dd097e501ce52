#ifndef vimlop_Registration_h
#define vimlop_Registration_h

#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/RegistrationResult.h>

#include <functional>

namespace vimlop
{

/// @brief Called after every iteration; return false to cancel the registration.
using IterationCallback = std::function<bool(const IterationRecord&)>;

/**
 * @brief Registers video data to the CT model: estimates T = [s, R, t] from
 * the SfM frame to the CT frame, starting from `initialSfmToCT`.
 *
 * Each iteration matches (3-D most likely points, V2; model occluding contours
 * from the current cameras, V3, their visibility, V4, and oriented 2-D
 * matches, V5), rejects outliers (V8), updates T by Levenberg-Marquardt (V6)
 * within the scale bounds (V7) with equal influence of 3-D and 2-D data (V9),
 * backs the update off while a camera would leave the airway (V10), and stops
 * on convergence or at the iteration cap (V11). `options.method` selects
 * V-IMLOP or one of the baselines (IMLP, trimmed ICP) in the same framework.
 *
 * @throws vimlop::Error for unusable input, with the reason: invalid data or
 * options, an initial scale outside the bounds, no contour points in any
 * frame (V-IMLOP), or a camera that starts outside the model surface.
 */
RegistrationResult registerVideo(const RegistrationModel& model, const RegistrationData& data,
  const SimilarityTransform& initialSfmToCT, const RegistrationOptions& options,
  const IterationCallback& callback = IterationCallback());

} // namespace vimlop

#endif
