#include <vimlop/Pipeline/EndoscopeTrackerOptions.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

namespace vimlop
{

void EndoscopeTrackerOptions::validate() const
{
  auto refuse = [](const char* what, double value)
  { throw Error(formatText("endoscope tracker: %s, not %g", what, value)); };
  if (this->maxFeatures < 10)
  {
    refuse("at least 10 features are needed", this->maxFeatures);
  }
  if (this->redetectBelow < 0 || this->redetectBelow > this->maxFeatures)
  {
    refuse(
      "new corners must be sought below a count in [0, the most features]", this->redetectBelow);
  }
  if (!(this->inlierThresholdPx > 0.0))
  {
    refuse("the inlier threshold must be positive (px)", this->inlierThresholdPx);
  }
  if (this->minInliers < 6)
  {
    refuse("a pose needs at least 6 inliers", this->minInliers);
  }
  if (!(this->degradedInlierFraction >= 0.0 && this->degradedInlierFraction <= 1.0))
  {
    refuse("the degraded inlier fraction must lie in [0, 1]", this->degradedInlierFraction);
  }
  if (!(this->maxJumpMm > 0.0))
  {
    refuse("the largest jump must be positive (mm)", this->maxJumpMm);
  }
  if (this->maxCoastFrames < 0)
  {
    refuse("the frames coasted must not be negative", this->maxCoastFrames);
  }
  if (!(this->maxTurnDeg > 0.0))
  {
    refuse("the largest turn must be positive (degrees)", this->maxTurnDeg);
  }
  if (!(this->maxDepthMm > 0.0))
  {
    refuse("the largest depth must be positive (mm)", this->maxDepthMm);
  }
  if (this->maxTrackingWidthPx < 64)
  {
    refuse("frames must be tracked at least 64 px wide", this->maxTrackingWidthPx);
  }
  if (!(this->minIncidenceCosine >= 0.0 && this->minIncidenceCosine < 1.0))
  {
    refuse("the least incidence cosine must lie in [0, 1)", this->minIncidenceCosine);
  }
  if (!(this->maxTipDistanceMm > 0.0))
  {
    refuse(
      "the largest distance from the tracker's tip must be positive (mm)", this->maxTipDistanceMm);
  }
  if (this->recastFromTrackerAfterFrames < 0)
  {
    refuse("the frames before features are cast from the tracker's pose must not be negative",
      this->recastFromTrackerAfterFrames);
  }
  if (this->trackerOffsetFrames < 0)
  {
    refuse("the frames the tracker's offset is learned over must not be negative",
      this->trackerOffsetFrames);
  }
  if (this->trackerOffsetPriorFrames < 0)
  {
    refuse(
      "the tracker's offset prior frames must not be negative", this->trackerOffsetPriorFrames);
  }
  if (!(this->trackerPull >= 0.0 && this->trackerPull <= 1.0))
  {
    refuse("the pull towards the tracker's pose must lie in [0, 1]", this->trackerPull);
  }
  if (!(this->maxTrackerTurnDeg > 0.0))
  {
    refuse("the largest turn from the tracker's rotation must be positive (degrees)",
      this->maxTrackerTurnDeg);
  }
  this->features.validate();
}

} // namespace vimlop
