#include <vimlop/Pipeline/TrackingSupervisor.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/TextFormat.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace vimlop
{

TrackingSupervisor::TrackingSupervisor(const FrameContourCheck& check,
  std::optional<ContourWindowRefinementOptions> refinement, bool relocalise,
  ContourRelocalisationOptions relocalisation, double registeredErrorPx)
  : Check(check)
  , Relocalise(relocalise)
  , Relocalisation(relocalisation)
{
  this->Relocalisation.registeredErrorPx = registeredErrorPx;
  this->Relocalisation.validate();
  if (refinement)
  {
    refinement->registeredErrorPx = registeredErrorPx;
    this->Refinement.emplace(*refinement);
  }
  // The first search needs no wait.
  this->SinceSearch = this->Relocalisation.retryFrames;
}

FrameContourAgreement TrackingSupervisor::judge(const cv::Mat& idealFrame, TrackedFrame& tracked)
{
  this->Contours = this->Check.detect(idealFrame);
  this->Judged = true;
  FrameContourAgreement agreement = this->Check.agreement(this->Contours, tracked.cameraToCT);
  const double limitPx = this->Relocalisation.degradedLimitPx();
  if (tracked.state == TrackingState::Tracking && agreement.medianErrorPx > limitPx)
  {
    tracked.state = TrackingState::Degraded;
    tracked.reason = formatText(
      "its contours lie %.1f px from the model's, above %.1f px", agreement.medianErrorPx, limitPx);
  }
  return agreement;
}

CheckedTrackedFrame TrackingSupervisor::follow(
  EndoscopeTracker& tracker, const TrackedFrame& tracked, const FrameContourAgreement& agreement)
{
  if (!this->Judged)
  {
    throw Error("tracking supervisor: follow() a frame that judge() checked");
  }
  this->Judged = false;
  CheckedTrackedFrame r;
  const ContourRelocalisationOptions& o = this->Relocalisation;
  const bool lost = tracked.state == TrackingState::Lost;
  // A lost frame's pose is a prediction, which moves neither with the frames
  // before it nor with those after (tracked against features cast from
  // it): the window starts again after it.
  if (lost)
  {
    this->Window.clear();
  }
  else
  {
    this->Window.push_back({ std::move(this->Contours), tracked.cameraToCT });
    while (static_cast<int>(this->Window.size()) > o.windowFrames)
    {
      this->Window.pop_front();
    }
  }
  // Only a tracker that lost its anchor to the CT is searched for, and only
  // when the contours clearly disagree with it: a frame whose contours alone
  // disagree is flagged, not moved, since the contours alone also fit poses
  // millimetres and degrees off (Documentation/Tracking.md).
  this->UnanchoredInARow = lost ? this->UnanchoredInARow
    : tracked.anchored          ? 0
                                : this->UnanchoredInARow + 1;
  // After a loss longer than the prediction carries the scope, its contours
  // cannot confirm a pose: on the bundled CT one frame's contours also fit
  // poses 3 mm off within 1.5 px (evaluate tracking with wall contact, seed
  // 5: 240 frames over 2 mm reported tracking when they did).
  if (lost)
  {
    ++this->LostInARow;
  }
  else
  {
    this->LongLoss =
      !tracked.anchored && (this->LongLoss || this->LostInARow > tracker.options().maxCoastFrames);
    this->LostInARow = 0;
  }
  ++this->SinceSearch;
  if (this->Relocalise && !lost && this->SinceSearch >= o.retryFrames &&
    this->UnanchoredInARow >= o.triggerFrames && agreement.medianErrorPx > o.degradedLimitPx())
  {
    this->SinceSearch = 0;
    r.searched = true;
    const auto began = std::chrono::steady_clock::now();
    const RelocalisationResult found = relocaliseAgainstCT(
      this->Check, std::vector<RelocalisationFrame>(this->Window.begin(), this->Window.end()), o);
    r.searchMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count();
    r.searchTrackedErrorPx = found.trackedErrorPx;
    r.searchBestErrorPx = found.bestErrorPx;
    if (found.correction)
    {
      // Moved, not anchored: whether the pose found is right, the next
      // frames' contours confirm (anchorErrorPx), as after any loss. One
      // frame's contours also fit wrong poses; anchoring them would report
      // such poses as tracking.
      r.relocalised = true;
      r.corrected = found.correction->apply(tracked.cameraToCT);
      r.correctionMm = cameraPositionError(*r.corrected, tracked.cameraToCT);
      tracker.correct(*r.corrected, false);
      // The frames before stand for poses the tracker left.
      this->Window.clear();
      if (this->Refinement)
      {
        this->Refinement->clear();
      }
      return r;
    }
  }
  if (!this->Refinement)
  {
    return r;
  }
  if (lost)
  {
    this->Refinement->clear();
    return r;
  }
  r.corrected = this->Refinement->add(this->Check.camera(), tracked.cameraToCT, agreement.pairs);
  // After a long loss the electromagnetic tracker, when there is one, tells
  // the poses the contours also fit apart: by its tip, and by its rotation
  // when it has one.
  const ContourWindowRefinementOptions& refinement = this->Refinement->options();
  const bool asTracked = tracked.tipDistanceMm &&
    *tracked.tipDistanceMm <= refinement.anchorTipDistanceMm &&
    tracked.trackerTurnDeg.value_or(0.0) <= refinement.anchorTrackerTurnDeg;
  r.anchored =
    (!this->LongLoss || asTracked) && agreement.medianErrorPx <= refinement.anchorErrorPx;
  if (r.corrected)
  {
    r.correctionMm = cameraPositionError(*r.corrected, tracked.cameraToCT);
    tracker.correct(*r.corrected, r.anchored);
  }
  else if (r.anchored && !tracked.anchored)
  {
    // Confirmed as it is, after a loss.
    tracker.correct(tracked.cameraToCT, true);
  }
  return r;
}

} // namespace vimlop
