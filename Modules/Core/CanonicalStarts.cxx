#include <vimlop/Core/CanonicalStarts.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/MultiStartRegistration.h>

#include <algorithm>

namespace vimlop
{

std::vector<SimilarityTransform> canonicalStarts(const RegistrationData& data, double initialScale,
  const std::vector<CameraPose>& posesCT, int* anchorFrameId)
{
  const size_t anchor = canonicalAnchorIndex(data);
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

std::size_t canonicalAnchorIndex(const RegistrationData& data)
{
  if (data.frames.empty())
  {
    throw Error("canonical starts: no registered frame");
  }
  return data.frames.size() / 2;
}

std::vector<CameraPose> turnedAsTracked(
  const std::vector<CameraPose>& canonicalCT, const CameraPose& tracked, double mergeMm)
{
  std::vector<CameraPose> poses = { tracked };
  for (const CameraPose& canonical : canonicalCT)
  {
    const bool seen = std::any_of(poses.begin() + 1, poses.end(),
      [&](const CameraPose& p) { return (p.centre - canonical.centre).norm() < mergeMm; });
    if (!seen)
    {
      poses.push_back({ tracked.rotation, canonical.centre });
    }
  }
  return poses;
}

} // namespace vimlop
