#ifndef vimlop_CanonicalStarts_h
#define vimlop_CanonicalStarts_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/SimilarityTransform.h>

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

} // namespace vimlop

#endif
