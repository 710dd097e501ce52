#include <vimlop/Pipeline/EndoscopeTracker.h>

#include "ErrorMessage.h"
#include "RenderedSequence.h"
#include <vimlop/Core/RegistrationMetrics.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdio>

namespace vimlop
{
namespace
{

TEST(EndoscopeTracker, FollowsTheRenderedScopeFromItsFirstRegisteredFrame)
{
  // The tracker starts from frame 0's true pose (a perfect registration) and
  // follows the rest of the sequence from the pictures alone. The model is
  // the rendered surface (the ideal world): 0.07 mm and 0.41 degrees at
  // most when this test was written.
  const fixtures::Sequence& s = fixtures::sequence();
  EndoscopeTracker tracker(s.mesh, s.intrinsics);
  const TrackedFrame first = tracker.start(s.frames[0], s.poses[0]);
  EXPECT_EQ(first.frame, 0);
  EXPECT_GE(first.newFeatures, tracker.options().minInliers);
  double largestMm = 0.0;
  double largestDeg = 0.0;
  for (std::size_t f = 1; f < s.frames.size(); ++f)
  {
    const TrackedFrame r = tracker.track(s.frames[f]);
    const double mm = cameraPositionError(r.cameraToCT, s.poses[f]);
    const double deg = cameraAngleErrorDeg(r.cameraToCT, s.poses[f]);
    std::printf("frame %2zu: %s, %3d tracked, %3d inliers, %.2f px, %3d new, %.3f mm, %.3f deg, "
                "%.1f ms\n",
      f, toString(r.state), r.trackedFeatures, r.inliers, r.reprojectionErrorPx, r.newFeatures, mm,
      deg, r.latencyMs);
    EXPECT_EQ(r.frame, static_cast<int>(f));
    EXPECT_EQ(r.state, TrackingState::Tracking) << f;
    EXPECT_GE(r.inliers, tracker.options().minInliers) << f;
    EXPECT_LE(r.inliers, r.trackedFeatures) << f;
    EXPECT_LT(r.reprojectionErrorPx, tracker.options().inlierThresholdPx) << f;
    EXPECT_GT(r.latencyMs, 0.0);
    largestMm = std::max(largestMm, mm);
    largestDeg = std::max(largestDeg, deg);
  }
  EXPECT_LT(largestMm, 0.2);
  EXPECT_LT(largestDeg, 1.0);
}

TEST(EndoscopeTracker, TracksAWideFrameHalvedAsItsOwnCamera)
{
  // The rendered frames enlarged to 640 x 480, with the camera that sees
  // them (twice the focal length; pixel centres at 2 (x + 0.5) - 0.5): the
  // tracker halves them back (maxTrackingWidthPx 480) and follows them as
  // well as the frames themselves. Its camera for the halved frames sees a
  // point where the halving takes the full frame's pixel: the poses alone
  // would not tell a wrong one (the model points are cast through the same
  // camera that finds the poses, so a 2 % focal error moved them by less
  // than 0.2 mm over this sequence).
  const fixtures::Sequence& s = fixtures::sequence();
  PinholeCamera wide = s.intrinsics;
  wide.widthPx *= 2;
  wide.heightPx *= 2;
  wide.fx *= 2.0;
  wide.fy *= 2.0;
  wide.cx = 2.0 * (s.intrinsics.cx + 0.5) - 0.5;
  wide.cy = 2.0 * (s.intrinsics.cy + 0.5) - 0.5;
  const auto enlarged = [&](const cv::Mat& frame)
  {
    cv::Mat large;
    cv::resize(frame, large, cv::Size(wide.widthPx, wide.heightPx), 0, 0, cv::INTER_LINEAR);
    return large;
  };
  EndoscopeTracker tracker(s.mesh, wide);
  const PinholeCamera& tracked = tracker.trackedCamera();
  EXPECT_EQ(tracked.widthPx, 320);
  EXPECT_EQ(tracked.heightPx, 240);
  for (const Eigen::Vector3d& point : { Eigen::Vector3d(0.0, 0.0, 20.0),
         Eigen::Vector3d(-7.0, 4.0, 15.0), Eigen::Vector3d(9.0, -6.0, 30.0) })
  {
    const Eigen::Vector2d full = wide.project(point);
    const Eigen::Vector2d halved = (full.array() + 0.5) / 2.0 - 0.5;
    EXPECT_LT((tracked.project(point) - halved).norm(), 1e-9) << point.transpose();
  }
  tracker.start(enlarged(s.frames[0]), s.poses[0],
    cv::Mat(wide.heightPx, wide.widthPx, CV_8U, cv::Scalar(255)));
  double largestMm = 0.0;
  for (std::size_t f = 1; f < s.frames.size(); ++f)
  {
    const TrackedFrame r = tracker.track(enlarged(s.frames[f]));
    EXPECT_EQ(r.state, TrackingState::Tracking) << f;
    largestMm = std::max(largestMm, cameraPositionError(r.cameraToCT, s.poses[f]));
  }
  EXPECT_LT(largestMm, 0.2);
  // A mask of the frames' size is what start() takes; another is refused.
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] {
                tracker.start(
                  enlarged(s.frames[0]), s.poses[0], cv::Mat(240, 320, CV_8U, cv::Scalar(255)));
              }),
    "endoscope tracker: a field-of-view mask of 320 x 240 pixels for frames of 640 x 480");
}

TEST(EndoscopeTracker, IsLostOnABlankFrameThenFollowsAgainDegraded)
{
  // Frame 8 is black (the scope against the wall, a flash of smoke): it and
  // the next frame are lost, reported at the constant-velocity prediction,
  // and the frames after are followed again, from features cast from that
  // prediction: degraded, since nothing checked them against the CT.
  const fixtures::Sequence& s = fixtures::sequence();
  EndoscopeTracker tracker(s.mesh, s.intrinsics);
  tracker.start(s.frames[0], s.poses[0]);
  const cv::Mat black = cv::Mat::zeros(s.frames[0].size(), s.frames[0].type());
  for (std::size_t f = 1; f < s.frames.size(); ++f)
  {
    const TrackedFrame r = tracker.track(f == 8 ? black : s.frames[f]);
    const double mm = cameraPositionError(r.cameraToCT, s.poses[f]);
    std::printf("frame %2zu: %s, %3d tracked, %3d inliers, %3d new, %.3f mm\n", f,
      toString(r.state), r.trackedFeatures, r.inliers, r.newFeatures, mm);
    if (f == 8 || f == 9)
    {
      EXPECT_EQ(r.state, TrackingState::Lost) << f;
      EXPECT_EQ(r.inliers, 0) << f;
    }
    else
    {
      EXPECT_EQ(r.state, f < 8 ? TrackingState::Tracking : TrackingState::Degraded) << f;
      EXPECT_GT(r.inliers, tracker.options().minInliers) << f;
    }
    // Each frame that is not tracking says why.
    const std::string why = f < 8 ? ""
      : f == 8                    ? "no pose agrees with 0 tracked features"
      : f == 9 ? "0 features left, fewer than 25: new ones are cast from the prediction"
               : "its features were cast from a prediction after the tracker was lost";
    EXPECT_EQ(r.reason, why) << f;
    // The prediction carries the lost frames: the path is smooth.
    EXPECT_LT(mm, 0.5) << f;
  }
}

/// What the electromagnetic tracker gives in largestErrorAfterABlackStretch().
enum class GivenPrior
{
  None,
  Tip,
  TipAndRotation
};

/// The largest camera errors over frames 11-15.
struct LargestErrors
{
  double mm = 0.0;
  double deg = 0.0;
};

/// An electromagnetic tracker's error: a shift (mm, CT frame) and a turn
/// (degrees about the CT's x axis) of every reading.
struct TrackerError
{
  Eigen::Vector3d shiftMm = Eigen::Vector3d::Zero();
  double turnDeg = 0.0;
};

/// The largest camera errors over frames 11-15 after frames 5-9 were black,
/// the tracker given the true optical centre as the electromagnetic
/// tracker's tip at every frame (and the true rotation as a 6-DOF
/// tracker's), or not, each off by `error`; the prediction holds the last
/// pose from the first lost frame on (maxCoastFrames 0), as it does after a
/// long loss. The tracker's error is learned over `offsetFrames` (0: not
/// learned), shrunk as if `priorFrames` had seen none. Also checks, for an exact tracker taken as
/// it reads, that each lost frame after the first is reported at the tip, and turned as the tracker
/// says when it has a rotation.
LargestErrors largestErrorAfterABlackStretch(
  GivenPrior given, const TrackerError& error = {}, int offsetFrames = 0, int priorFrames = 0)
{
  const fixtures::Sequence& s = fixtures::sequence();
  EndoscopeTrackerOptions o;
  o.maxCoastFrames = 0;
  o.trackerOffsetFrames = offsetFrames;
  o.trackerOffsetPriorFrames = priorFrames;
  EndoscopeTracker tracker(s.mesh, s.intrinsics, o);
  const Eigen::Matrix3d turn =
    Eigen::AngleAxisd(error.turnDeg * M_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const bool exact = error.shiftMm.isZero() && error.turnDeg == 0.0 && offsetFrames == 0;
  tracker.start(s.frames[0], s.poses[0]);
  const cv::Mat black = cv::Mat::zeros(s.frames[0].size(), s.frames[0].type());
  LargestErrors largest;
  for (std::size_t f = 1; f < s.frames.size(); ++f)
  {
    const bool blank = f >= 5 && f <= 9;
    std::optional<TrackerPrior> prior;
    if (given == GivenPrior::Tip)
    {
      prior = TrackerPrior(s.poses[f].centre + error.shiftMm);
    }
    else if (given == GivenPrior::TipAndRotation)
    {
      prior = TrackerPrior(s.poses[f].centre + error.shiftMm, turn * s.poses[f].rotation);
    }
    const TrackedFrame r = tracker.track(blank ? black : s.frames[f], prior);
    const double mm = cameraPositionError(r.cameraToCT, s.poses[f]);
    const double deg = cameraAngleErrorDeg(r.cameraToCT, s.poses[f]);
    std::printf("frame %2zu: %s, %.3f mm, %.3f deg\n", f, toString(r.state), mm, deg);
    if (blank && f > 5 && prior && exact)
    {
      EXPECT_EQ(r.state, TrackingState::Lost) << f;
      EXPECT_LT(mm, 1e-12) << f;
      if (given == GivenPrior::TipAndRotation)
      {
        EXPECT_LT(deg, 1e-6) << f;
      }
    }
    if (f > 10)
    {
      EXPECT_NE(r.state, TrackingState::Lost) << f;
      largest.mm = std::max(largest.mm, mm);
      largest.deg = std::max(largest.deg, deg);
    }
  }
  return largest;
}

TEST(EndoscopeTracker, TakesTheCentreOfALostFrameFromTheTrackersTip)
{
  // Over a black stretch of five frames the scope moves on: without a
  // tracker the prediction holds where it was lost, the features of the
  // first frame after the stretch are cast from there, and the frames after
  // it keep that error. With the tip as the prediction's centre they are
  // cast from where the scope is (with the orientation it was lost with):
  // 3.04 mm at most without the tip and 0.22 mm with it when this test was
  // written.
  const double without = largestErrorAfterABlackStretch(GivenPrior::None).mm;
  const double with = largestErrorAfterABlackStretch(GivenPrior::Tip).mm;
  std::printf(
    "largest error after the stretch: %.3f mm without the tip, %.3f mm with it\n", without, with);
  EXPECT_LT(with, 0.25 * without);
  EXPECT_LT(with, 0.4);
}

TEST(EndoscopeTracker, TakesTheRotationOfALostFrameFromASixDofTracker)
{
  // The same stretch with a 6-DOF tracker: the lost frames are reported at
  // its pose, and the features after the stretch are cast from the pose the
  // scope has rather than from the orientation it was lost with.
  const LargestErrors tip = largestErrorAfterABlackStretch(GivenPrior::Tip);
  const LargestErrors pose = largestErrorAfterABlackStretch(GivenPrior::TipAndRotation);
  std::printf("largest error after the stretch: %.3f mm, %.3f deg with the tip; %.3f mm, %.3f deg "
              "with its rotation too\n",
    tip.mm, tip.deg, pose.mm, pose.deg);
  EXPECT_LT(pose.deg, tip.deg);
  EXPECT_LT(pose.mm, 0.4);
}

TEST(EndoscopeTracker, LearnsASixDofTrackersErrorWhileAnchoredAndTakesItOffAfterALoss)
{
  // A 6-DOF tracker 1 mm and 2 degrees off, as a navigation system's
  // registration leaves it. Taken as it reads, the frames after the black
  // stretch are cast from its pose and keep its error; learned over the
  // four tracked frames before the stretch, taken as enough (no
  // shrinkage), its error is taken off, and they are cast from where the
  // scope is. Shrunk as by default (as if 30 frames had seen no error), 4
  // frames take off little of it.
  TrackerError error;
  error.shiftMm = Eigen::Vector3d(0.6, -0.48, 0.64);
  error.turnDeg = 2.0;
  const LargestErrors asRead = largestErrorAfterABlackStretch(GivenPrior::TipAndRotation, error, 0);
  const LargestErrors learned =
    largestErrorAfterABlackStretch(GivenPrior::TipAndRotation, error, 90, 0);
  const LargestErrors shrunk = largestErrorAfterABlackStretch(
    GivenPrior::TipAndRotation, error, 90, EndoscopeTrackerOptions().trackerOffsetPriorFrames);
  std::printf("largest error after the stretch, the tracker 1 mm and 2 deg off: %.3f mm, %.3f deg "
              "as it reads; %.3f mm, %.3f deg with its error learned; %.3f mm, %.3f deg "
              "learned and shrunk\n",
    asRead.mm, asRead.deg, learned.mm, learned.deg, shrunk.mm, shrunk.deg);
  EXPECT_GT(asRead.mm, 0.5);
  EXPECT_LT(learned.mm, 0.5 * asRead.mm);
  EXPECT_LT(learned.deg, 0.5 * asRead.deg);
  EXPECT_GT(shrunk.mm, 0.7 * asRead.mm);
}

TEST(EndoscopeTracker, DegradesAPoseFartherThanAllowedFromTheTrackersTip)
{
  // The video and the electromagnetic tracker disagree by more than a
  // navigation system's error: the pose is not trusted (whichever is
  // wrong). Within the limit it is. (The tracker is taken as it reads: its
  // error learned from frame 1 would move the limit by frame 2.)
  const fixtures::Sequence& s = fixtures::sequence();
  EndoscopeTrackerOptions asRead;
  asRead.trackerOffsetFrames = 0;
  EndoscopeTracker tracker(s.mesh, s.intrinsics, asRead);
  tracker.start(s.frames[0], s.poses[0]);
  const Eigen::Vector3d sideways = s.poses[1].rotation.col(0);
  const TrackedFrame near =
    tracker.track(s.frames[1], TrackerPrior(s.poses[1].centre + 2.0 * sideways));
  EXPECT_EQ(near.state, TrackingState::Tracking);
  const TrackedFrame far =
    tracker.track(s.frames[2], TrackerPrior(s.poses[2].centre + 5.0 * sideways));
  EXPECT_EQ(far.state, TrackingState::Degraded);
  EXPECT_EQ(far.reason, "the pose is 5.0 mm from the tracker's tip, more than 3.0 mm");
  // The pose is the video's: the tip only judges it.
  EXPECT_LT(cameraPositionError(far.cameraToCT, s.poses[2]), 0.1);
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] { tracker.track(s.frames[3], Eigen::Vector3d(0.0, std::nan(""), 0.0)); }),
    "endoscope tracker: the tracker's tip position is not finite");
}

TEST(EndoscopeTracker, DegradesAPoseTurnedFromASixDofTrackersRotationByMoreThanAllowed)
{
  // A 6-DOF tracker whose rotation is the truth turned about the view axis:
  // 3 degrees is within the 5 allowed, 8 degrees is not. Either way the
  // pose is the video's. (Taken as it reads, as above.)
  const fixtures::Sequence& s = fixtures::sequence();
  EndoscopeTrackerOptions asRead;
  asRead.trackerOffsetFrames = 0;
  EndoscopeTracker tracker(s.mesh, s.intrinsics, asRead);
  tracker.start(s.frames[0], s.poses[0]);
  const auto turned = [&](std::size_t f, double deg)
  {
    const Eigen::Vector3d view = s.poses[f].rotation.col(2);
    return TrackerPrior(s.poses[f].centre,
      Eigen::AngleAxisd(deg * M_PI / 180.0, view).toRotationMatrix() * s.poses[f].rotation);
  };
  const TrackedFrame near = tracker.track(s.frames[1], turned(1, 3.0));
  EXPECT_EQ(near.state, TrackingState::Tracking) << near.reason;
  ASSERT_TRUE(near.trackerTurnDeg.has_value());
  EXPECT_NEAR(*near.trackerTurnDeg, 3.0, 0.5);
  const TrackedFrame far = tracker.track(s.frames[2], turned(2, 8.0));
  EXPECT_EQ(far.state, TrackingState::Degraded);
  EXPECT_EQ(far.reason.substr(0, 18), "the pose is turned");
  EXPECT_NE(far.reason.find("degrees from the tracker's, more than 5.0 degrees"), std::string::npos)
    << far.reason;
  EXPECT_LT(cameraAngleErrorDeg(far.cameraToCT, s.poses[2]), 0.5);
  // A position-only tracker says nothing of the turn.
  EXPECT_FALSE(tracker.track(s.frames[3], TrackerPrior(s.poses[3].centre)).trackerTurnDeg);
  Eigen::Matrix3d sheared = s.poses[4].rotation;
  sheared(0, 1) += 0.1;
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] { tracker.track(s.frames[4], TrackerPrior(s.poses[4].centre, sheared)); }),
    "endoscope tracker: the tracker's rotation is not a rotation matrix");
}

/// The largest camera error over frames 8-15 of the tracker started from
/// frame 0 at a pose 4 mm sideways of the truth (a wrong registration,
/// whose features make a world 4 mm off), given a 6-DOF tracker at the
/// truth, with the features cast again from the tracker's pose after
/// `recastAfter` frames that disagree with it (0: never).
double largestErrorFromAWrongStartWithASixDofTracker(int recastAfter)
{
  const fixtures::Sequence& s = fixtures::sequence();
  EndoscopeTrackerOptions o;
  o.recastFromTrackerAfterFrames = recastAfter;
  EndoscopeTracker tracker(s.mesh, s.intrinsics, o);
  CameraPose wrong = s.poses[0];
  wrong.centre += 4.0 * s.poses[0].rotation.col(0);
  tracker.start(s.frames[0], wrong);
  double largestMm = 0.0;
  for (std::size_t f = 1; f < s.frames.size(); ++f)
  {
    const TrackedFrame r =
      tracker.track(s.frames[f], TrackerPrior(s.poses[f].centre, s.poses[f].rotation));
    const double mm = cameraPositionError(r.cameraToCT, s.poses[f]);
    std::printf("frame %2zu: %s (%s), %.3f mm\n", f, toString(r.state), r.reason.c_str(), mm);
    EXPECT_NE(r.state, TrackingState::Tracking) << f;
    if (recastAfter > 0 && static_cast<int>(f) == recastAfter)
    {
      EXPECT_EQ(r.reason,
        "the pose disagreed with the tracker for 5 frames in a row: features cast again from "
        "the tracker's pose");
      EXPECT_LT(mm, 1e-12);
    }
    if (f >= 8)
    {
      largestMm = std::max(largestMm, mm);
    }
  }
  return largestMm;
}

TEST(EndoscopeTracker, CastsItsFeaturesAgainFromASixDofTrackerItHasDisagreedWithForFiveFrames)
{
  // Started 4 mm off, the features follow a world 4 mm off and every pose
  // is degraded for its distance from the tracker's tip; after five such
  // frames they are cast again from the tracker's pose, and the poses come
  // back to the scope (still degraded: nothing has confirmed them against
  // the CT).
  const double never = largestErrorFromAWrongStartWithASixDofTracker(0);
  const double recast = largestErrorFromAWrongStartWithASixDofTracker(5);
  std::printf(
    "largest error on frames 8-15: %.3f mm never cast again, %.3f mm cast again\n", never, recast);
  EXPECT_GT(never, 3.0);
  EXPECT_LT(recast, 0.5);
}

TEST(EndoscopeTracker, HoldsAFiniteRotationThroughALongLostStretch)
{
  // After a few tracked frames the picture goes black for 200 frames. The
  // prediction coasts on for maxCoastFrames, then holds: every pose stays a
  // rotation (each prediction multiplied the last two, and without
  // re-orthonormalising their rounding grew to infinity within 100 frames)
  // and near where the scope was lost.
  const fixtures::Sequence& s = fixtures::sequence();
  EndoscopeTracker tracker(s.mesh, s.intrinsics);
  tracker.start(s.frames[0], s.poses[0]);
  TrackedFrame last;
  for (std::size_t f = 1; f < 6; ++f)
  {
    last = tracker.track(s.frames[f]);
  }
  ASSERT_EQ(last.state, TrackingState::Tracking);
  const cv::Mat black = cv::Mat::zeros(s.frames[0].size(), s.frames[0].type());
  const double stepMm = (s.poses[5].centre - s.poses[4].centre).norm();
  for (int f = 0; f < 200; ++f)
  {
    const TrackedFrame r = tracker.track(black);
    ASSERT_EQ(r.state, TrackingState::Lost) << f;
    ASSERT_TRUE(r.cameraToCT.rotation.allFinite()) << f;
    ASSERT_LT(
      (r.cameraToCT.rotation.transpose() * r.cameraToCT.rotation - Eigen::Matrix3d::Identity())
        .norm(),
      1e-9)
      << f;
    ASSERT_LT((r.cameraToCT.centre - last.cameraToCT.centre).norm(),
      (tracker.options().maxCoastFrames + 1) * stepMm + 0.5)
      << f;
  }
}

TEST(EndoscopeTracker, DetectsCornersOnlyInsideTheFieldOfView)
{
  // A field of view of nothing leaves no corner to start from; the right
  // half of the frame is enough to follow the scope.
  const fixtures::Sequence& s = fixtures::sequence();
  EndoscopeTracker tracker(s.mesh, s.intrinsics);
  const cv::Mat none = cv::Mat::zeros(s.frames[0].size(), CV_8U);
  EXPECT_EQ(fixtures::errorMessageOf([&] { tracker.start(s.frames[0], s.poses[0], none); }),
    "endoscope tracker: only 0 corners of the first frame stand for a point of the model (at "
    "least 25 needed): is the camera inside the airway, and the frame textured?");
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] { tracker.start(s.frames[0], s.poses[0], cv::Mat::zeros(10, 10, CV_8U)); }),
    "endoscope tracker: a field-of-view mask of 10 x 10 pixels for frames of 320 x 240");
  cv::Mat right = none.clone();
  right.colRange(right.cols / 2, right.cols).setTo(255);
  tracker.start(s.frames[0], s.poses[0], right);
  for (std::size_t f = 1; f < 6; ++f)
  {
    const TrackedFrame r = tracker.track(s.frames[f]);
    EXPECT_NE(r.state, TrackingState::Lost) << f;
    EXPECT_LT(cameraPositionError(r.cameraToCT, s.poses[f]), 0.3) << f;
  }
}

TEST(EndoscopeTracker, DoesNotBelieveAPoseThatJumpsOrTurnsMoreThanAllowed)
{
  // The scope moves 0.5 mm a frame and turns by a fraction of a degree:
  // with limits far below that, no pose is believed, and every frame is
  // lost, reported at the prediction.
  const fixtures::Sequence& s = fixtures::sequence();
  for (int limit = 0; limit < 2; ++limit)
  {
    EndoscopeTrackerOptions o;
    (limit == 0 ? o.maxJumpMm : o.maxTurnDeg) = 1e-3;
    EndoscopeTracker tracker(s.mesh, s.intrinsics, o);
    tracker.start(s.frames[0], s.poses[0]);
    for (std::size_t f = 1; f < 4; ++f)
    {
      const TrackedFrame r = tracker.track(s.frames[f]);
      EXPECT_EQ(r.state, TrackingState::Lost) << limit << " " << f;
      EXPECT_EQ(r.inliers, 0) << limit << " " << f;
      EXPECT_GT(r.trackedFeatures, o.minInliers) << limit << " " << f;
    }
  }
}

TEST(EndoscopeTracker, FollowsThePoseItIsCorrectedTo)
{
  // Started 0.5 mm off frame 0's true pose, the tracker keeps about that
  // error (its features stand for points cast from the wrong pose); corrected
  // to frame 7's true pose, it follows the truth from there.
  const fixtures::Sequence& s = fixtures::sequence();
  EndoscopeTracker tracker(s.mesh, s.intrinsics);
  CameraPose off = s.poses[0];
  off.centre += off.rotation.col(0) * 0.5;
  tracker.start(s.frames[0], off);
  double before = 0.0;
  for (std::size_t f = 1; f <= 7; ++f)
  {
    before = cameraPositionError(tracker.track(s.frames[f]).cameraToCT, s.poses[f]);
  }
  EXPECT_GT(before, 0.3);
  EXPECT_GE(tracker.correct(s.poses[7], true), tracker.options().minInliers);
  for (std::size_t f = 8; f < s.frames.size(); ++f)
  {
    const TrackedFrame r = tracker.track(s.frames[f]);
    EXPECT_EQ(r.state, TrackingState::Tracking) << f;
    EXPECT_LT(cameraPositionError(r.cameraToCT, s.poses[f]), 0.15) << f;
  }
}

} // namespace
} // namespace vimlop
