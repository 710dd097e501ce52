#include <vimlop/Pipeline/ContourWindowRefinement.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/SimilarityTransform.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Core/VideoFrame.h>

#include <algorithm>
#include <cmath>

namespace vimlop
{

void ContourWindowRefinementOptions::validate() const
{
  auto refuse = [](const char* what, double value)
  { throw Error(formatText("contour refinement: %s, not %g", what, value)); };
  if (this->windowFrames < 1)
  {
    refuse("the window needs at least 1 frame", this->windowFrames);
  }
  if (this->minPairs < 6)
  {
    refuse("at least 6 contour pairs are needed", this->minPairs);
  }
  if (!(this->maxCorrectionMm > 0.0) || !(this->maxCorrectionDeg > 0.0))
  {
    refuse("the largest correction must be positive (mm, degrees)",
      this->maxCorrectionMm > 0.0 ? this->maxCorrectionDeg : this->maxCorrectionMm);
  }
  if (!(this->minErrorPx >= 0.0))
  {
    refuse("the least contour error to correct must not be negative (px)", this->minErrorPx);
  }
  if (!(this->registeredErrorPx >= 0.0))
  {
    refuse("the registration's contour error must not be negative (px)", this->registeredErrorPx);
  }
  if (!(this->anchorTipDistanceMm > 0.0))
  {
    refuse("the anchoring distance from the tracker's tip must be positive (mm)",
      this->anchorTipDistanceMm);
  }
  if (!(this->anchorTrackerTurnDeg > 0.0))
  {
    refuse("the anchoring turn from the tracker's rotation must be positive (degrees)",
      this->anchorTrackerTurnDeg);
  }
  if (!(this->anchorErrorPx >= 0.0))
  {
    refuse("the anchoring contour error must not be negative (px)", this->anchorErrorPx);
  }
}

ContourWindowRefinement::ContourWindowRefinement(const ContourWindowRefinementOptions& options)
  : Options(options)
{
  options.validate();
}

void ContourWindowRefinement::clear()
{
  this->Window.clear();
}

std::optional<CameraPose> ContourWindowRefinement::add(
  const PinholeCamera& camera, const CameraPose& cameraToCT, const std::vector<ContourPair>& pairs)
{
  this->Window.push_back({ camera, cameraToCT, pairs });
  while (static_cast<int>(this->Window.size()) > this->Options.windowFrames)
  {
    this->Window.pop_front();
  }
  // The window as the pose update sees a registration's data: its "SfM"
  // frame is the CT, each camera at its tracked pose, T the correction.
  std::vector<VideoFrame> frames;
  PoseUpdateProblem problem;
  for (const Frame& f : this->Window)
  {
    const int index = static_cast<int>(frames.size());
    frames.push_back({ index, f.camera, f.cameraToCT, {} });
    for (ContourPair p : f.pairs)
    {
      p.frame = index;
      problem.contours.push_back(p);
    }
  }
  if (static_cast<int>(problem.contours.size()) < this->Options.minPairs)
  {
    return std::nullopt;
  }
  const double leastPx = std::max(this->Options.minErrorPx, this->Options.registeredErrorPx);
  if (leastPx > 0.0)
  {
    std::vector<double> errorsPx;
    errorsPx.reserve(problem.contours.size());
    for (const ContourPair& p : problem.contours)
    {
      const VideoFrame& f = frames[static_cast<std::size_t>(p.frame)];
      errorsPx.push_back(
        (f.intrinsics.project(f.cameraToSfm.worldToCamera(p.modelPoint)) - p.videoPixel).norm());
    }
    if (summarize(std::move(errorsPx)).median <= leastPx)
    {
      return std::nullopt;
    }
  }
  problem.frames = &frames;
  problem.minScale = 1.0;
  problem.maxScale = 1.0;
  const PoseUpdateResult update = solvePoseUpdate(problem, SimilarityTransform());
  if (!(update.finalCost < update.initialCost))
  {
    return std::nullopt;
  }
  const CameraPose corrected = update.transform.apply(cameraToCT);
  if (!(cameraPositionError(corrected, cameraToCT) <= this->Options.maxCorrectionMm) ||
    !(cameraAngleErrorDeg(corrected, cameraToCT) <= this->Options.maxCorrectionDeg))
  {
    return std::nullopt;
  }
  for (Frame& f : this->Window)
  {
    f.cameraToCT = update.transform.apply(f.cameraToCT);
  }
  return corrected;
}

} // namespace vimlop
