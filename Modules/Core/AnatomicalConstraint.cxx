#include <vimlop/Core/AnatomicalConstraint.h>

namespace vimlop
{

bool camerasInside(const RegistrationModel& model, const std::vector<VideoFrame>& frames,
  const SimilarityTransform& sfmToCT, int* outsideFrameId)
{
  for (const VideoFrame& frame : frames)
  {
    if (!model.isInside(sfmToCT.apply(frame.cameraToSfm.centre)))
    {
      if (outsideFrameId)
      {
        *outsideFrameId = frame.frameId;
      }
      return false;
    }
  }
  return true;
}

SimilarityTransform backOffIntoAirway(const RegistrationModel& model,
  const std::vector<VideoFrame>& frames, const SimilarityTransform& previous,
  const SimilarityTransform& next, int maxBackoffSteps, int& steps)
{
  steps = 0;
  if (camerasInside(model, frames, next))
  {
    return next;
  }
  const Vector7d change = next.compose(previous.inverse()).log();
  double fraction = 1.0;
  for (steps = 1; steps <= maxBackoffSteps; ++steps)
  {
    fraction *= 0.5;
    const SimilarityTransform trial = SimilarityTransform::exp(fraction * change).compose(previous);
    if (camerasInside(model, frames, trial))
    {
      return trial;
    }
  }
  return previous;
}

} // namespace vimlop
