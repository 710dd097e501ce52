#ifndef vimlop_TrackingSupervisor_h
#define vimlop_TrackingSupervisor_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Pipeline/ContourRelocalisation.h>
#include <vimlop/Pipeline/ContourWindowRefinement.h>
#include <vimlop/Pipeline/EndoscopeTracker.h>
#include <vimlop/Pipeline/FrameContourCheck.h>

#include <opencv2/core/mat.hpp>

#include <deque>
#include <optional>
#include <vector>

namespace vimlop
{

/// @brief A tracked frame after what followed its pose (TrackingSupervisor::follow()).
struct CheckedTrackedFrame
{
  /// The frame's pose corrected against the CT, when the tracker was corrected.
  std::optional<CameraPose> corrected;
  /// How far that correction moved the camera, mm (0: not corrected).
  double correctionMm = 0.0;
  /// Whether the check confirmed the pose (re-anchoring the tracker).
  bool anchored = false;
  /// Whether a relocalisation was searched after this frame, and whether it
  /// moved the tracker (then `corrected` is its pose).
  bool searched = false;
  bool relocalised = false;
  /// The search's contour errors, px: at the tracked poses and the lowest
  /// it found (0 when not searched).
  double searchTrackedErrorPx = 0.0;
  double searchBestErrorPx = 0.0;
  /// The search's wall-clock time, ms (0 when not searched).
  double searchMs = 0.0;
};

/**
 * @brief What watches the tracker against the CT (issue 16), one frame
 * after another, in two steps:
 *   1. judge(), before the pose is handed on (inside its latency): the
 *      frame's contours are checked at the tracked pose (FrameContourCheck);
 *      a frame whose contours lie farther from the model's than
 *      ContourRelocalisationOptions::degradedLimitPx() is reported Degraded,
 *      so that a navigation system never shows such a pose as good;
 *   2. follow(), after: when enough frames in a row were tracked from
 *      features cast from a prediction (the tracker lost its anchor to the
 *      CT) and the contours clearly disagree, a relocalisation against the CT
 *      (relocaliseAgainstCT()) moves the tracker to the pose it finds (the
 *      next frames' contours anchor it when they agree); otherwise the
 *      window refinement (ContourWindowRefinement), when on, corrects the
 *      small drift and anchors the tracker when the contours agree (unless
 *      it was lost for longer than its prediction coasts,
 *      EndoscopeTrackerOptions::maxCoastFrames: then only a pose near the
 *      electromagnetic tracker's tip, TrackedFrame::tipDistanceMm within
 *      ContourWindowRefinementOptions::anchorTipDistanceMm, and turned as a
 *      6-DOF tracker says, TrackedFrame::trackerTurnDeg within
 *      anchorTrackerTurnDeg, or a new start anchors it). Frames that only their contours distrust
 * are flagged, not searched for (ContourRelocalisationOptions::triggerFrames says why). vimlop
 * track (VideoTracking) and evaluate tracking (TrackingProtocol) both run it. Not thread-safe: one
 * per tracker.
 */
class TrackingSupervisor
{
public:
  /**
   * @param check the contour check (kept by reference: it must outlive this)
   * @param refinement the window refinement's settings; none: no refinement
   * @param relocalise whether to search when the tracker lost its anchor
   * @param relocalisation the limits of trust and the search (its
   * registeredErrorPx and the refinement's are set to `registeredErrorPx`)
   * @param registeredErrorPx the registration's contour error, px (0: unknown)
   * @throws vimlop::Error for invalid settings.
   */
  TrackingSupervisor(const FrameContourCheck& check,
    std::optional<ContourWindowRefinementOptions> refinement, bool relocalise,
    ContourRelocalisationOptions relocalisation, double registeredErrorPx);

  /**
   * @brief Checks `tracked` (the tracker's last frame, `idealFrame`
   * undistorted) against the CT, and downgrades it to Degraded, with its
   * reason, when its contours lie above the limit.
   */
  FrameContourAgreement judge(const cv::Mat& idealFrame, TrackedFrame& tracked);

  /**
   * @brief After the frame judge() checked last: the relocalisation or the
   * refinement, given to the tracker (EndoscopeTracker::correct()).
   */
  CheckedTrackedFrame follow(
    EndoscopeTracker& tracker, const TrackedFrame& tracked, const FrameContourAgreement& agreement);

  const ContourRelocalisationOptions& relocalisation() const { return this->Relocalisation; }

private:
  const FrameContourCheck& Check;
  std::optional<ContourWindowRefinement> Refinement;
  bool Relocalise = true;
  ContourRelocalisationOptions Relocalisation;
  /// The last frames since a loss: contours and tracked pose.
  std::deque<RelocalisationFrame> Window;
  /// Frames tracked unanchored since the tracker was last anchored (lost
  /// frames not counted).
  int UnanchoredInARow = 0;
  /// Frames lost in a row, and whether the tracker has been unanchored since
  /// a loss longer than its prediction coasts (maxCoastFrames): its
  /// contours then no longer anchor it.
  int LostInARow = 0;
  bool LongLoss = false;
  /// The contours judge() detected in the last frame.
  std::vector<ContourPoint> Contours;
  bool Judged = false;
  /// Frames since the last search.
  int SinceSearch = 0;
};

} // namespace vimlop

#endif
