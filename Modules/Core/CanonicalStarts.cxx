#include <vimlop/Core/CanonicalStarts.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/MultiStartRegistration.h>

namespace vimlop
{

std::vector<SimilarityTransform> canonicalStarts(const RegistrationData& data, double initialScale,
  const std::vector<CameraPose>& posesCT, int* anchorFrameId)
{
  if (data.frames.empty())
  {
    throw Error("canonical starts: no registered frame");
  }
  const size_t anchor = data.frames.size() / 2;
  if (anchorFrameId)
  {
    *anchorFrameId = data.frames[anchor].frameId;
  }
  std::vector<SimilarityTransform> starts;
  for (const CameraPose& pose : posesCT)
  {
    starts.push_back(startFromCameraPose(pose, data.frames[anchor].cameraToSfm, initialScale));
  }
  return starts;
}

} // namespace vimlop
