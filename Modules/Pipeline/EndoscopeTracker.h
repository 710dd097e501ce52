#ifndef vimlop_EndoscopeTracker_h
#define vimlop_EndoscopeTracker_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Pipeline/EndoscopeTrackerOptions.h>
#include <vimlop/Pipeline/TrackerOffset.h>
#include <vimlop/Pipeline/TrackerPrior.h>
#include <vimlop/Video/KltFeatureTracker.h>

#include <opencv2/core/mat.hpp>

#include <memory>
#include <optional>
#include <string>

namespace vimlop
{

/// @brief How far a tracked pose can be trusted.
enum class TrackingState
{
  Tracking, ///< enough features agree with the pose
  /// A pose was found, but many tracked features disagree with it, or its
  /// features were cast from a prediction after the tracker was lost
  /// (nothing has checked them against the CT since, and a wrong prediction
  /// makes a wrong world that agrees with itself), or the frame's contours
  /// disagree with the CT's at the pose (TrackingSupervisor::judge()).
  Degraded,
  Lost ///< no pose from this frame: the pose reported is the prediction
};

/// @brief "tracking", "degraded" or "lost".
const char* toString(TrackingState state);

/// @brief What the tracker reports for one frame.
struct TrackedFrame
{
  int frame = 0; ///< index of the frame since start(), which is frame 0
  CameraPose cameraToCT;
  TrackingState state = TrackingState::Tracking;
  int trackedFeatures = 0; ///< features followed into this frame
  int inliers = 0;         ///< of those, the ones that agree with the pose
  /// Root mean square reprojection error of the inliers, in pixels of the
  /// frames as tracked (see EndoscopeTrackerOptions::maxTrackingWidthPx).
  double reprojectionErrorPx = 0.0;
  int newFeatures = 0; ///< corners added after the pose was found
  /// False when the features were cast from a prediction after a loss, or
  /// from a 6-DOF tracker's pose (recastFromTrackerAfterFrames), and no
  /// check against the CT has confirmed a pose since (correct()).
  bool anchored = true;
  /// How far the pose found lies from the electromagnetic tracker's tip,
  /// mm; none without a tip, or when no pose was found (Lost).
  std::optional<double> tipDistanceMm;
  /// The angle between the pose found and a 6-DOF tracker's rotation,
  /// degrees; none without one, or when no pose was found (Lost).
  std::optional<double> trackerTurnDeg;
  /// Wall-clock time of track(), from the frame to the pose and the new features, ms.
  double latencyMs = 0.0;
  /// Why the frame is Degraded or Lost, for people; empty when Tracking.
  std::string reason;
};

/**
 * @brief Follows the endoscope from frame to frame after a registration:
 * the live camera pose in the CT for navigation (issue 16).
 *
 * It starts from a registered frame and its camera pose in the CT. Each
 * feature stands for the point of the registered model surface that its
 * ray hits when it is detected, so the map it tracks against is the CT
 * model itself, seen through the registration. For every new frame it
 *   1. predicts the pose at constant velocity from the last two poses (after
 *      a lost frame, centred on the electromagnetic tracker's tip when given,
 *      and turned as a 6-DOF tracker says),
 *   2. tracks the features into the frame (KltFeatureTracker),
 *   3. finds the pose from them (resectCamera(): RANSAC from the
 *      prediction, then Levenberg-Marquardt on the inliers),
 *   4. judges it (TrackingState: inliers, their fraction, the jump from
 *      the prediction, the distance from the tip, the turn from a 6-DOF
 *      tracker's rotation),
 *   5. drops the outliers and, when few features are left, detects new
 *      corners and casts their rays into the model from the new pose; when
 *      the poses have disagreed with a 6-DOF tracker for
 *      recastFromTrackerAfterFrames frames, it casts new corners from the
 *      tracker's pose instead, and reports the frame there.
 *
 * With an electromagnetic tracker, the video and the tracker correct each
 * other: in Tracking frames the video, anchored to the CT, teaches the
 * tracker's error (trackerOffsetFrames, TrackerOffset), which is taken off
 * every prior; in frames not anchored, the pose found is pulled towards
 * the corrected tracker's (trackerPull), its features with it.
 *
 * A frame where no pose is found, or none that agrees with enough features
 * after the refinement, or one too far from the prediction (a jump or a
 * turn no hand makes between frames), is Lost and reported at the
 * prediction, which holds still after `maxCoastFrames` lost frames. When
 * fewer than `minInliers` features are left (after a blank or blurred
 * frame), the next frame is Lost too and its corners are cast from the
 * prediction, so tracking resumes by itself when the scope moved as
 * predicted. Whether it did, the features cannot tell: from then on frames
 * are at best Degraded, until a check against the CT confirms a pose
 * (correct(), anchored; see ContourWindowRefinement and
 * relocaliseAgainstCT(), which TrackingSupervisor calls) or the tracker is
 * started again.
 *
 * Frames are of the intrinsics' size; when the intrinsics carry a lens,
 * each frame is undistorted with it first (FrameUndistorter), and poses are
 * those of the pinhole camera with the same fx, fy, cx, cy. Not
 * thread-safe: one tracker per video stream.
 */
class EndoscopeTracker
{
public:
  /**
   * @param modelCT the registered model (CT frame, mm; normals into the air)
   * @param intrinsics the frames' camera, with its lens when they are distorted
   * @throws vimlop::Error for invalid options or intrinsics, or a mesh without faces.
   */
  EndoscopeTracker(const TriangleMesh& modelCT, const PinholeCamera& intrinsics,
    const EndoscopeTrackerOptions& options = {});
  ~EndoscopeTracker();
  EndoscopeTracker(const EndoscopeTracker&) = delete;
  EndoscopeTracker& operator=(const EndoscopeTracker&) = delete;

  /**
   * @brief Starts (or restarts) on `frame`, whose camera is at `cameraToCT`
   * (a registration's pose of that frame): detects its features and
   * the model points they stand for.
   * @param fieldOfViewMask where corners may be detected in the undistorted
   * frames (CV_8U, non-zero inside the field stop, e.g.
   * VideoRegistrationPipeline::fieldOfViewMask()); empty: everywhere. It is
   * shrunk by half a KLT window, so that no feature's window sees the
   * stop's edge, which stays still while the anatomy moves.
   * @throws vimlop::Error for a frame or mask of another size than the
   * intrinsics, or when too few corners stand for a point of the model (a
   * camera outside the airway, a frame without texture).
   */
  TrackedFrame start(
    const cv::Mat& frame, const CameraPose& cameraToCT, const cv::Mat& fieldOfViewMask = cv::Mat());

  /**
   * @brief The pose of the next frame.
   * @param prior what an electromagnetic tracker says of the camera at the
   * frame's time; none without a tracker. After a lost frame the
   * prediction takes its centre from the tip, and its rotation from a
   * 6-DOF tracker's, rather than from a motion no longer measured; a pose
   * farther from the tip than maxTipDistanceMm, or turned from the
   * tracker's rotation by more than maxTrackerTurnDeg, is Degraded; and
   * TrackingSupervisor lets a pose that agrees with it be confirmed after a
   * long loss.
   * @throws vimlop::Error before start(), for a frame of another size, or
   * for a tip that is not finite or a rotation that is not one.
   */
  TrackedFrame track(const cv::Mat& frame, const std::optional<TrackerPrior>& prior = std::nullopt);

  /**
   * @brief Moves the last tracked frame's pose to `cameraToCT`, a pose found
   * against the CT (e.g. by ContourWindowRefinement): the features' model
   * points are cast again from it (those whose ray now misses the model, or
   * meets it at a grazing angle, are dropped) and the prediction moves with
   * it. With `anchored`, the CT has confirmed the pose: frames after a loss
   * are no longer held Degraded for it, the prediction starts again from
   * rest when the frame was lost, and when fewer than `redetectBelow`
   * features are left, new corners of the last frame are cast from the pose.
   * @return the features kept or added.
   * @throws vimlop::Error before start().
   */
  int correct(const CameraPose& cameraToCT, bool anchored);

  const EndoscopeTrackerOptions& options() const;

  /// @brief The electromagnetic tracker's error learned so far
  /// (trackerOffsetFrames), taken off each prior.
  const TrackerOffset& trackerOffset() const;

  /// @brief The pinhole camera of the frames as tracked: undistorted, and
  /// halved as maxTrackingWidthPx asks (pixel centres at (x + 0.5) / s - 0.5
  /// for a frame s times smaller).
  const PinholeCamera& trackedCamera() const;

private:
  struct Internals;
  std::unique_ptr<Internals> d;
};

} // namespace vimlop

#endif
