#ifndef vimlop_AnatomicalConstraint_h
#define vimlop_AnatomicalConstraint_h

#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Core/SimilarityTransform.h>
#include <vimlop/Core/VideoFrame.h>

#include <vector>

/**
 * @file AnatomicalConstraint.h
 * @brief The anatomical constraint (V10): every camera stays inside the airway.
 */

namespace vimlop
{

/**
 * @brief True when T moves every frame's camera centre (SfM frame) to the air
 * side of the model surface (RegistrationModel::isInside).
 *
 * @param sfmToCT T, SfM frame to CT frame
 * @param outsideFrameId when given and a camera is outside, set to the
 *   `frameId` of the first such frame (in the order of `frames`); untouched otherwise
 */
bool camerasInside(const RegistrationModel& model, const std::vector<VideoFrame>& frames,
  const SimilarityTransform& sfmToCT, int* outsideFrameId = nullptr);

/**
 * @brief The update from `previous` to `next`, backed off until every camera
 * is inside (V10): `next` itself when it keeps them inside, else the first of
 * exp(f · log(next ∘ previous⁻¹)) ∘ previous for f = ½, ¼, … (at most
 * `maxBackoffSteps` halvings) that does, else `previous` (the update undone).
 * Backing off along the change, rather than projecting the cameras, keeps the
 * estimate on the path the pose update chose.
 *
 * @param steps set to the halvings applied: 0 when `next` was kept,
 *   `maxBackoffSteps` + 1 when the update was undone
 */
SimilarityTransform backOffIntoAirway(const RegistrationModel& model,
  const std::vector<VideoFrame>& frames, const SimilarityTransform& previous,
  const SimilarityTransform& next, int maxBackoffSteps, int& steps);

} // namespace vimlop

#endif
