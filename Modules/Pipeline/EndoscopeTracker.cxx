#include <vimlop/Pipeline/EndoscopeTracker.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Raycast/EmbreeScene.h>
#include <vimlop/Video/CameraResection.h>
#include <vimlop/Video/FrameUndistorter.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace vimlop
{

const char* toString(TrackingState state)
{
  switch (state)
  {
    case TrackingState::Degraded:
      return "degraded";
    case TrackingState::Lost:
      return "lost";
    case TrackingState::Tracking:
      break;
  }
  return "tracking";
}

/// A tracked feature: where it is in the current frame and the model point it stands for.
struct TrackedFeature
{
  Eigen::Vector2d pixel;
  Eigen::Vector3d pointCT;
};

struct EndoscopeTracker::Internals
{
  EndoscopeTrackerOptions Options;
  /// The lens of the frames given, and the pinhole camera of the frames once undistorted.
  FrameUndistorter Undistorter;
  PinholeCamera Intrinsics;
  /// Frames are tracked this many times smaller (a power of 2; 1: as they
  /// are), with this pinhole camera.
  int Shrink = 1;
  PinholeCamera Tracked;
  EmbreeScene Scene;
  KltFeatureTracker Klt;
  std::vector<TrackedFeature> Features;
  /// Where corners may be detected (empty: everywhere).
  cv::Mat Mask;
  /// The last two poses reported (the last one first), for the prediction.
  CameraPose Last;
  CameraPose BeforeLast;
  int Frame = -1;
  /// Frames lost since the last pose found.
  int LostInARow = 0;
  /// False once features were cast from a prediction (after a loss): the
  /// poses found from them are then not anchored to the registration.
  bool Anchored = true;
  /// Where the features were cast from when not anchored, for the reason
  /// given with each pose found from them.
  std::string CastFrom;
  /// Poses found in a row that disagree with a 6-DOF tracker (farther from
  /// its tip than maxTipDistanceMm, or turned more than maxTrackerTurnDeg);
  /// lost frames, which find none, leave the count as it is.
  int AwayFromTrackerInARow = 0;
  /// The electromagnetic tracker's error, as the anchored video saw it.
  TrackerOffset Offset;

  Internals(const TriangleMesh& mesh, const PinholeCamera& k, const EndoscopeTrackerOptions& o)
    : Options(o)
    , Offset(std::max(o.trackerOffsetFrames, 1), o.trackerOffsetPriorFrames)
    , Undistorter(k)
    , Intrinsics(Undistorter.pinhole())
    , Scene(mesh)
    , Klt(o.features)
  {
    while (this->Intrinsics.widthPx / this->Shrink > o.maxTrackingWidthPx)
    {
      this->Shrink *= 2;
    }
    // Pixel centres map as cv::resize's area mode maps them.
    this->Tracked = this->Intrinsics.resampled(1.0 / this->Shrink);
  }

  /// A frame as it is tracked: undistorted, and shrunk when it is wide.
  cv::Mat prepare(const cv::Mat& frame) const
  {
    const cv::Mat ideal = this->Undistorter.undistort(frame);
    if (this->Shrink == 1)
    {
      return ideal;
    }
    cv::Mat small;
    cv::resize(
      ideal, small, cv::Size(this->Tracked.widthPx, this->Tracked.heightPx), 0, 0, cv::INTER_AREA);
    return small;
  }

  void checkSize(const cv::Mat& frame) const
  {
    if (frame.cols != this->Intrinsics.widthPx || frame.rows != this->Intrinsics.heightPx)
    {
      throw Error(formatText("endoscope tracker: a frame of %d x %d pixels, but the intrinsics "
                             "are for %d x %d",
        frame.cols, frame.rows, this->Intrinsics.widthPx, this->Intrinsics.heightPx));
    }
  }

  /// coast(), after a lost frame centred on the tracker's tip and turned as
  /// a 6-DOF tracker says when there is one: a lost frame measured no
  /// motion to go on with.
  CameraPose predict(const std::optional<TrackerPrior>& prior) const
  {
    CameraPose next = this->coast();
    if (prior && this->LostInARow > 0)
    {
      next.centre = prior->tipCT;
      next.rotation = prior->rotationCT.value_or(next.rotation);
    }
    return next;
  }

  /// The next pose at constant velocity: the last motion, in the camera's
  /// own frame, applied once more; the last pose itself once the scope has
  /// been lost for maxCoastFrames frames in a row.
  CameraPose coast() const
  {
    if (this->LostInARow >= this->Options.maxCoastFrames)
    {
      return this->Last;
    }
    const Eigen::Matrix3d turn = this->BeforeLast.rotation.transpose() * this->Last.rotation;
    const Eigen::Vector3d step =
      this->BeforeLast.rotation.transpose() * (this->Last.centre - this->BeforeLast.centre);
    CameraPose next;
    // Back onto the rotations: each prediction multiplies the last two, and
    // over a lost stretch their rounding errors grew until the rotation
    // was infinite (a 600-frame run stopped on a ray cast from NaN).
    next.rotation = nearestRotation(this->Last.rotation * turn);
    next.centre = this->Last.centre + this->Last.rotation * step;
    return next;
  }

  /// The model point the ray of `pixel` (a pixel of the frames as tracked)
  /// from `pose` stands for: the first surface it meets within the largest
  /// depth, squarely enough; none when it misses or grazes the wall.
  std::optional<Eigen::Vector3d> castFeature(
    const CameraPose& pose, const Eigen::Vector2d& pixel) const
  {
    const Eigen::Vector3d ray = pose.rotation * this->Tracked.rayDirection(pixel);
    const std::optional<SurfacePoint> hit =
      this->Scene.castRay(pose.centre, ray, this->Options.maxDepthMm);
    if (!hit)
    {
      return std::nullopt;
    }
    const Eigen::Vector3d& normal =
      this->Scene.mesh().faceNormals()[static_cast<std::size_t>(hit->face)];
    if (std::abs(normal.dot(ray)) < this->Options.minIncidenceCosine)
    {
      return std::nullopt;
    }
    return hit->point;
  }

  /// Sets `r`'s distance from the tracker's tip and turn from its rotation.
  static void measureFromTracker(TrackedFrame& r, const std::optional<TrackerPrior>& sensor)
  {
    if (!sensor)
    {
      return;
    }
    r.tipDistanceMm = (r.cameraToCT.centre - sensor->tipCT).norm();
    if (sensor->rotationCT)
    {
      r.trackerTurnDeg =
        rotationAngleBetween(*sensor->rotationCT, r.cameraToCT.rotation) * 180.0 / M_PI;
    }
  }

  /// Casts the model points of `features` (pixels of the last frame) again
  /// from `pose`, dropping those whose ray now misses or grazes the wall.
  void recast(const CameraPose& pose, std::vector<TrackedFeature>& features) const
  {
    std::vector<TrackedFeature> kept;
    kept.reserve(features.size());
    for (const TrackedFeature& f : features)
    {
      if (const std::optional<Eigen::Vector3d> point = this->castFeature(pose, f.pixel))
      {
        kept.push_back({ f.pixel, *point });
      }
    }
    features = std::move(kept);
  }

  /// Moves `pose` trackerPull of the way to the tracker's, once the
  /// anchored video has checked its position (the caller's condition), and
  /// its rotation too once checked (TrackerOffset::rotationChecked()); casts
  /// `features` again from it. @return how far it moved, mm.
  double pullTowards(
    const TrackerPrior& sensor, CameraPose& pose, std::vector<TrackedFeature>& features) const
  {
    const double pull = this->Options.trackerPull;
    const Eigen::Vector3d before = pose.centre;
    pose.centre += pull * (sensor.tipCT - pose.centre);
    if (sensor.rotationCT && this->Offset.rotationChecked())
    {
      pose.rotation = rotationTowards(pose.rotation, *sensor.rotationCT, pull);
    }
    this->recast(pose, features);
    return (pose.centre - before).norm();
  }

  /// Forgets the features and casts new corners of `ideal` (a prepared
  /// frame) from `pose`: the features of a new start, or of one after the
  /// old ones stood for a wrong world. @return the features added.
  int castAfresh(const cv::Mat& ideal, const CameraPose& pose)
  {
    this->Klt.reset(ideal);
    this->Features.clear();
    return this->addFeatures(pose);
  }

  /// Detects corners where no feature is and adds those whose ray from
  /// `pose` meets the model squarely enough; returns how many were added.
  int addFeatures(const CameraPose& pose)
  {
    const int wanted = this->Options.maxFeatures - static_cast<int>(this->Features.size());
    std::vector<Eigen::Vector2d> existing;
    existing.reserve(this->Features.size());
    for (const TrackedFeature& f : this->Features)
    {
      existing.push_back(f.pixel);
    }
    int added = 0;
    for (const Eigen::Vector2d& pixel : this->Klt.detect(wanted, existing, this->Mask))
    {
      if (const std::optional<Eigen::Vector3d> point = this->castFeature(pose, pixel))
      {
        this->Features.push_back({ pixel, *point });
        ++added;
      }
    }
    return added;
  }
};

EndoscopeTracker::EndoscopeTracker(const TriangleMesh& modelCT, const PinholeCamera& intrinsics,
  const EndoscopeTrackerOptions& options)
{
  options.validate();
  intrinsics.validate();
  this->d = std::make_unique<Internals>(modelCT, intrinsics, options);
}

EndoscopeTracker::~EndoscopeTracker() = default;

int EndoscopeTracker::correct(const CameraPose& cameraToCT, bool anchored)
{
  Internals& s = *this->d;
  if (s.Frame < 0)
  {
    throw Error("endoscope tracker: start() on a registered frame first");
  }
  // The same rigid move for the pose before, so that the prediction keeps
  // the scope's own motion.
  const Eigen::Matrix3d turn = cameraToCT.rotation * s.Last.rotation.transpose();
  s.BeforeLast.centre = cameraToCT.centre + turn * (s.BeforeLast.centre - s.Last.centre);
  s.BeforeLast.rotation = nearestRotation(turn * s.BeforeLast.rotation);
  s.Last = cameraToCT;
  s.recast(cameraToCT, s.Features);
  s.Anchored = s.Anchored || anchored;
  if (anchored)
  {
    // The CT has confirmed the video's world, whatever the tracker says.
    s.AwayFromTrackerInARow = 0;
    if (s.LostInARow > 0)
    {
      // The motion between two predictions is no measured motion.
      s.BeforeLast = cameraToCT;
      s.LostInARow = 0;
    }
    if (static_cast<int>(s.Features.size()) < s.Options.redetectBelow)
    {
      s.addFeatures(cameraToCT);
    }
  }
  return static_cast<int>(s.Features.size());
}

const EndoscopeTrackerOptions& EndoscopeTracker::options() const
{
  return this->d->Options;
}

const TrackerOffset& EndoscopeTracker::trackerOffset() const
{
  return this->d->Offset;
}

const PinholeCamera& EndoscopeTracker::trackedCamera() const
{
  return this->d->Tracked;
}

TrackedFrame EndoscopeTracker::start(
  const cv::Mat& frame, const CameraPose& cameraToCT, const cv::Mat& fieldOfViewMask)
{
  const auto began = std::chrono::steady_clock::now();
  Internals& s = *this->d;
  s.checkSize(frame);
  s.Mask = cv::Mat();
  if (!fieldOfViewMask.empty())
  {
    if (fieldOfViewMask.size() != frame.size())
    {
      throw Error(formatText("endoscope tracker: a field-of-view mask of %d x %d pixels for "
                             "frames of %d x %d",
        fieldOfViewMask.cols, fieldOfViewMask.rows, frame.cols, frame.rows));
    }
    cv::Mat inside = fieldOfViewMask != 0;
    if (s.Shrink > 1)
    {
      cv::resize(
        inside, inside, cv::Size(s.Tracked.widthPx, s.Tracked.heightPx), 0, 0, cv::INTER_NEAREST);
    }
    const int halfWindow = s.Options.features.windowPx / 2;
    cv::erode(inside, s.Mask,
      cv::getStructuringElement(
        cv::MORPH_ELLIPSE, cv::Size(2 * halfWindow + 1, 2 * halfWindow + 1)));
  }
  s.Frame = -1;
  const int added = s.castAfresh(s.prepare(frame), cameraToCT);
  if (added < s.Options.minInliers)
  {
    throw Error(formatText("endoscope tracker: only %d corners of the first frame stand for a "
                           "point of the model (at least %d needed): is the camera inside the "
                           "airway, and the frame textured?",
      added, s.Options.minInliers));
  }
  s.Frame = 0;
  s.LostInARow = 0;
  s.Anchored = true;
  s.AwayFromTrackerInARow = 0;
  s.Offset.clear();
  s.Last = cameraToCT;
  s.BeforeLast = cameraToCT;
  TrackedFrame r;
  r.cameraToCT = cameraToCT;
  r.newFeatures = added;
  r.trackedFeatures = added;
  r.inliers = added;
  r.latencyMs =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count();
  return r;
}

TrackedFrame EndoscopeTracker::track(const cv::Mat& frame, const std::optional<TrackerPrior>& prior)
{
  const auto began = std::chrono::steady_clock::now();
  Internals& s = *this->d;
  if (s.Frame < 0)
  {
    throw Error("endoscope tracker: start() on a registered frame first");
  }
  s.checkSize(frame);
  const cv::Mat ideal = s.prepare(frame);
  if (prior && !prior->tipCT.allFinite())
  {
    throw Error("endoscope tracker: the tracker's tip position is not finite");
  }
  if (prior && prior->rotationCT && !isRotation(*prior->rotationCT, 1e-6))
  {
    throw Error("endoscope tracker: the tracker's rotation is not a rotation matrix");
  }
  // The tracker with the error the anchored video has taught it taken off.
  const std::optional<TrackerPrior> sensor =
    prior ? std::optional<TrackerPrior>(s.Offset.corrected(*prior)) : std::nullopt;
  const CameraPose predicted = s.predict(sensor);
  TrackedFrame r;
  r.frame = ++s.Frame;
  // Until a pose is found: lost, at the prediction.
  r.cameraToCT = predicted;
  r.state = TrackingState::Lost;
  auto finish = [&]
  {
    r.anchored = s.Anchored;
    s.LostInARow = r.state == TrackingState::Lost ? s.LostInARow + 1 : 0;
    s.BeforeLast = s.Last;
    s.Last = r.cameraToCT;
    r.latencyMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count();
    return r;
  };
  if (static_cast<int>(s.Features.size()) < s.Options.minInliers)
  {
    // Too few features to find a pose (after a blank or blurred frame): this
    // frame is lost, and its corners, cast into the model from the
    // prediction, are the next frames' features. When the scope moved as
    // predicted, they stand for the right points and tracking resumes.
    r.reason = formatText("%zu features left, fewer than %d: new ones are cast from the "
                          "prediction",
      s.Features.size(), s.Options.minInliers);
    r.newFeatures = s.castAfresh(ideal, r.cameraToCT);
    s.Anchored = false;
    s.CastFrom = "a prediction after the tracker was lost";
    return finish();
  }

  std::vector<Eigen::Vector2d> pixels;
  pixels.reserve(s.Features.size());
  for (const TrackedFeature& f : s.Features)
  {
    pixels.push_back(f.pixel);
  }
  const std::vector<char> kept = s.Klt.track(ideal, pixels);
  std::vector<TrackedFeature> followed;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> seen;
  for (std::size_t i = 0; i < kept.size(); ++i)
  {
    if (kept[i])
    {
      followed.push_back({ pixels[i], s.Features[i].pointCT });
      points.push_back(s.Features[i].pointCT);
      seen.push_back(pixels[i]);
    }
  }

  r.trackedFeatures = static_cast<int>(followed.size());
  CameraResectionOptions pnp;
  pnp.thresholdPx = s.Options.inlierThresholdPx;
  pnp.iterations = 100;
  pnp.solver = ResectionSolver::IterativeFromGuess;
  const std::optional<CameraResection> pose =
    resectCamera(points, seen, s.Tracked, pnp, &predicted);
  // Why the pose is not believed; empty when it is.
  const double jumpMm = pose ? (pose->cameraToWorld.centre - predicted.centre).norm() : 0.0;
  const double turnDeg = pose
    ? rotationAngleBetween(predicted.rotation, pose->cameraToWorld.rotation) * 180.0 / M_PI
    : 0.0;
  if (!pose)
  {
    r.reason = formatText("no pose agrees with %d tracked features", r.trackedFeatures);
  }
  else if (static_cast<int>(pose->inliers.size()) < s.Options.minInliers)
  {
    r.reason = formatText("%zu features agree with the pose, fewer than %d", pose->inliers.size(),
      s.Options.minInliers);
  }
  else if (pose->rmsErrorPx > s.Options.inlierThresholdPx)
  {
    r.reason = formatText("the features' reprojection error %.2f px is above %.2f px",
      pose->rmsErrorPx, s.Options.inlierThresholdPx);
  }
  else if (jumpMm > s.Options.maxJumpMm)
  {
    r.reason = formatText("the pose is %.1f mm from the prediction", jumpMm);
  }
  else if (turnDeg > s.Options.maxTurnDeg)
  {
    r.reason = formatText("the pose is turned %.1f degrees from the prediction", turnDeg);
  }
  if (r.reason.empty())
  {
    r.cameraToCT = pose->cameraToWorld;
    r.inliers = static_cast<int>(pose->inliers.size());
    r.reprojectionErrorPx = pose->rmsErrorPx;
    s.measureFromTracker(r, sensor);
    const double tipMm = r.tipDistanceMm.value_or(0.0);
    const double trackerTurnDeg = r.trackerTurnDeg.value_or(0.0);
    const bool awayFromTracker =
      tipMm > s.Options.maxTipDistanceMm || trackerTurnDeg > s.Options.maxTrackerTurnDeg;
    s.AwayFromTrackerInARow =
      awayFromTracker && sensor && sensor->rotationCT ? s.AwayFromTrackerInARow + 1 : 0;
    if (!s.Anchored)
    {
      r.reason = "its features were cast from " + s.CastFrom;
    }
    else if (r.inliers < s.Options.degradedInlierFraction * r.trackedFeatures)
    {
      r.reason =
        formatText("%d of %d tracked features agree with the pose", r.inliers, r.trackedFeatures);
    }
    else if (tipMm > s.Options.maxTipDistanceMm)
    {
      r.reason = formatText("the pose is %.1f mm from the tracker's tip, more than %.1f mm", tipMm,
        s.Options.maxTipDistanceMm);
    }
    else if (trackerTurnDeg > s.Options.maxTrackerTurnDeg)
    {
      r.reason =
        formatText("the pose is turned %.1f degrees from the tracker's, more than %.1f degrees",
          trackerTurnDeg, s.Options.maxTrackerTurnDeg);
    }
    r.state = r.reason.empty() ? TrackingState::Tracking : TrackingState::Degraded;
    if (r.state == TrackingState::Tracking && prior && s.Options.trackerOffsetFrames > 0)
    {
      s.Offset.learn(r.cameraToCT, *prior);
    }
    // Only the features that agree with the pose are worth following.
    std::vector<TrackedFeature> agreeing;
    agreeing.reserve(pose->inliers.size());
    for (int i : pose->inliers)
    {
      agreeing.push_back(followed[static_cast<std::size_t>(i)]);
    }
    followed = std::move(agreeing);
  }
  if (r.state == TrackingState::Lost)
  {
    // Their model points were right for the last pose found; the next
    // frame sees whether they agree again.
    s.Features = std::move(followed);
    return finish();
  }
  const int recastAfter = s.Options.recastFromTrackerAfterFrames;
  if (recastAfter > 0 && s.AwayFromTrackerInARow >= recastAfter)
  {
    // The features have made a world that a 6-DOF tracker has contradicted
    // for that long (cast into a model that is not the anatomy, or from a
    // wrong prediction after a loss): the frame is reported at the
    // tracker's pose, and its corners, cast from there, are the next
    // frames' features.
    r.reason = formatText("the pose disagreed with the tracker for %d frames in a row: "
                          "features cast again from the tracker's pose",
      recastAfter);
    r.cameraToCT.centre = sensor->tipCT;
    r.cameraToCT.rotation = *sensor->rotationCT;
    r.tipDistanceMm = 0.0;
    r.trackerTurnDeg = 0.0;
    r.newFeatures = s.castAfresh(ideal, r.cameraToCT);
    s.Anchored = false;
    s.CastFrom = "the tracker's pose, which the video disagreed with";
    s.AwayFromTrackerInARow = 0;
    TrackedFrame done = finish();
    // From rest: the move to the tracker's pose is no motion of the scope.
    s.BeforeLast = s.Last;
    return done;
  }
  if (!s.Anchored && sensor && s.Options.trackerPull > 0.0 && s.Offset.positionChecked())
  {
    // Nothing has checked this world against the CT: the tracker says where
    // the scope is, the video how it moved since the last frame.
    const double pulledMm = s.pullTowards(*sensor, r.cameraToCT, followed);
    s.measureFromTracker(r, sensor);
    r.reason += formatText(", pulled %.2f mm towards the tracker's pose", pulledMm);
  }
  s.Features = std::move(followed);
  if (static_cast<int>(s.Features.size()) < s.Options.redetectBelow)
  {
    r.newFeatures = s.addFeatures(r.cameraToCT);
  }
  return finish();
}

} // namespace vimlop
