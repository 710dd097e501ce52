#ifndef vimlop_CanonicalStarts_h
#define vimlop_CanonicalStarts_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/SimilarityTransform.h>

#include <cstddef>
#include <vector>

namespace vimlop
{

/**
 * @brief One start per canonical pose (V13 b): the middle registered frame
 * placed at the pose, at the scale `initialScale` (mm per SfM unit), so that
 * the sequence reaches both ways from it, as the scope moves through the
 * region. The id of that frame goes to `anchorFrameId` when given.
 * @throws vimlop::Error when the data have no frame.
 */
std::vector<SimilarityTransform> canonicalStarts(const RegistrationData& data, double initialScale,
  const std::vector<CameraPose>& posesCT, int* anchorFrameId = nullptr);

/**
 * @brief The frame canonicalStarts() places at each pose: the middle
 * registered frame, as its index in `data.frames`.
 * @throws vimlop::Error when the data have no frame.
 */
std::size_t canonicalAnchorIndex(const RegistrationData& data);

/**
 * @brief Canonical poses under a rotation prior: an electromagnetic tracker
 * registered to the patient says how the camera is turned (`tracked`, the
 * anchor frame's camera-to-CT pose from the tracker), the canonical poses
 * where in the airway it may be. The result is the tracked pose itself,
 * then one pose per distinct canonical position (closer than `mergeMm`
 * counts as the same) turned as the tracker says: the views and rolls of
 * each position give way to the tracked rotation, which a roll of the scope
 * the canonical rolls do not hold cannot fool.
 */
std::vector<CameraPose> turnedAsTracked(
  const std::vector<CameraPose>& canonicalCT, const CameraPose& tracked, double mergeMm = 0.5);

} // namespace vimlop

#endif
