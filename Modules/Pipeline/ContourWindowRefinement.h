#ifndef vimlop_ContourWindowRefinement_h
#define vimlop_ContourWindowRefinement_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/PoseUpdate.h>
#include <vimlop/Pipeline/FrameContourCheck.h>

#include <deque>
#include <optional>
#include <vector>

namespace vimlop
{

/// @brief Settings of ContourWindowRefinement, each with its reason.
struct ContourWindowRefinementOptions
{
  /// Frames whose contours are registered together (default 5): one frame's
  /// contours confuse a small sideways shift with a small turn, as its
  /// features do; frames seen from a moving scope tell them apart.
  int windowFrames = 5;
  /// Fewer contour pairs than this over the window and nothing is corrected
  /// (default 50).
  int minPairs = 50;
  /// A correction that moves the camera farther than this, mm, or turns it
  /// by more than maxCorrectionDeg, is not applied (defaults 1 mm and 2
  /// degrees): tracking drifts by hundredths of a millimetre per frame, so a
  /// larger correction more likely comes from wrong matches (a video edge
  /// the model lacks). Taking such a correction part of the way instead
  /// sent seed 4 of `evaluate tracking` 19.5 mm off: steps towards wrong
  /// matches add up.
  double maxCorrectionMm = 1.0;
  double maxCorrectionDeg = 2.0;
  /// The window is corrected only when its contours lie farther than this
  /// from the model's (the median distance over its pairs at the cameras'
  /// current poses), px (default 1.5). At the true pose the detector leaves
  /// 0.5-1.3 px (median over frames, ideal world), and correcting that moved
  /// good poses: with 0, seed 1 of `evaluate tracking` went from 0.184 mm
  /// and 0.45 degrees to 0.204 mm and 0.76 degrees (Documentation/Tracking.md).
  double minErrorPx = 1.5;
  /// The registration's own contour error, px (TrackingStart::contourErrorPx;
  /// default 0): the window is corrected only when its contours lie farther
  /// than this too. Where the model is not the anatomy (swelling, a template
  /// warp), the contours disagree with it at the true pose by as much as the
  /// registration left (13 px on the clinical world's seed 3), and
  /// correcting towards them sent that run's camera 44 degrees off.
  double registeredErrorPx = 0.0;
  /// A frame whose contours lie within this median distance of the model's
  /// after the correction confirms the pose against the CT (default 1.5 px:
  /// in the ideal world 0.5 px at the true pose, 2-3 px at 0.25-1 mm from
  /// it), which re-anchors a tracker that was lost.
  double anchorErrorPx = 1.5;
  /// After a loss longer than the prediction carries the scope, contours
  /// within anchorErrorPx anchor the tracker only when its pose also lies
  /// within this distance of the electromagnetic tracker's tip, mm (default
  /// 1: one frame's contours also fit poses 3 mm off on the bundled CT, and
  /// the simulated tracker's tip lies 0.35 mm from the truth, root mean
  /// square).
  double anchorTipDistanceMm = 1.0;
  /// With a 6-DOF tracker, its rotation must agree too: the pose turned
  /// from it by at most this, degrees (default 2: the simulated sensor's
  /// rotation lies 0.5 degrees from the truth on average, a real one's
  /// calibration to the camera adds a degree or so, and poses the contours
  /// also fit are turned by several degrees).
  double anchorTrackerTurnDeg = 2.0;

  /// @throws vimlop::Error naming the first value out of range.
  void validate() const;
};

/**
 * @brief Refinement of the tracked pose against the CT on a sliding window
 * of frames (issue 16): the rigid move of the last frames' cameras that
 * best lays their occluding contours on the model's (the V-IMLOP pose
 * update, V6, on contours alone, scale fixed at 1).
 *
 * The 3-D points of the tracker stand for model points cast from its own
 * poses: they lie on the model whatever the drift, so they are left out;
 * only the contours, from the pictures and the CT alone, pull the cameras
 * back. Each frame adds its contour pairs, matched at its tracked pose
 * (FrameContourCheck); the correction is applied to every camera of the
 * window, so a frame's pairs keep counting at its corrected pose until it
 * leaves the window.
 */
class ContourWindowRefinement
{
public:
  explicit ContourWindowRefinement(const ContourWindowRefinementOptions& options = {});

  /**
   * @brief Adds a frame, seen by `camera` (pinhole, undistorted) from
   * `cameraToCT`, with its contour pairs, and registers the window.
   * @return the frame's corrected pose, or none when nothing is corrected
   * (too few pairs, contours already within minErrorPx, no decrease of the
   * cost, or a correction above the bounds).
   */
  std::optional<CameraPose> add(const PinholeCamera& camera, const CameraPose& cameraToCT,
    const std::vector<ContourPair>& pairs);

  /// @brief Forgets the window (after a loss: its cameras no longer follow the scope).
  void clear();

  const ContourWindowRefinementOptions& options() const { return this->Options; }

private:
  struct Frame
  {
    PinholeCamera camera;
    CameraPose cameraToCT;
    std::vector<ContourPair> pairs;
  };
  ContourWindowRefinementOptions Options;
  std::deque<Frame> Window;
};

} // namespace vimlop

#endif
