#include <vimlop/Pipeline/TrackingSupervisor.h>

#include "RenderedSequence.h"
#include <vimlop/Core/RegistrationMetrics.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdio>

namespace vimlop
{
namespace
{

TEST(TrackingSupervisor, JudgesAPoseTheContoursDisagreeWithDegradedAndSaysWhy)
{
  // A frame the tracker reports tracking, at its true pose and 1.5 mm aside:
  // the first stays tracking, the second is degraded, with its contour error.
  const fixtures::Sequence& s = fixtures::sequence();
  const FrameContourCheck check(*s.model, s.intrinsics, cv::Mat());
  TrackingSupervisor supervisor(check, std::nullopt, false, {}, 0.0);
  TrackedFrame atTruth;
  atTruth.cameraToCT = s.poses[5];
  const FrameContourAgreement good = supervisor.judge(s.frames[5], atTruth);
  EXPECT_EQ(atTruth.state, TrackingState::Tracking);
  EXPECT_LT(good.medianErrorPx, 1.5);
  TrackedFrame aside = atTruth;
  aside.cameraToCT.centre += aside.cameraToCT.rotation.col(0) * 1.5;
  const FrameContourAgreement bad = supervisor.judge(s.frames[5], aside);
  EXPECT_EQ(aside.state, TrackingState::Degraded);
  char why[100];
  std::snprintf(
    why, sizeof why, "its contours lie %.1f px from the model's, above 6.0 px", bad.medianErrorPx);
  EXPECT_EQ(aside.reason, why);
  EXPECT_GT(bad.medianErrorPx, 6.0);
}

TEST(TrackingSupervisor, FlagsATrackerStartedOffWithoutSearchingOnContoursAlone)
{
  // The tracker starts 1.5 mm aside and 4 degrees turned from frame 0's true
  // pose (a registration that missed): its features stand for points cast
  // from that pose, so they mostly agree with it, but the frames' contours
  // do not. Those frames are reported degraded. The tracker is anchored (it
  // started from a registration): contours alone do not move it, since in a
  // narrow passage they also fit poses far off.
  const fixtures::Sequence& s = fixtures::sequence();
  const FrameContourCheck check(*s.model, s.intrinsics, cv::Mat());
  TrackingSupervisor supervisor(check, std::nullopt, true, {}, 0.0);
  EndoscopeTracker tracker(s.mesh, s.intrinsics);
  CameraPose off = s.poses[0];
  off.rotation =
    off.rotation * Eigen::AngleAxisd(4.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).matrix();
  off.centre += off.rotation.col(0) * 1.5;
  tracker.start(s.frames[0], off);
  for (std::size_t f = 1; f < 6; ++f)
  {
    TrackedFrame t = tracker.track(s.frames[f]);
    const FrameContourAgreement a = supervisor.judge(s.frames[f], t);
    const CheckedTrackedFrame c = supervisor.follow(tracker, t, a);
    EXPECT_EQ(t.state, TrackingState::Degraded) << f;
    EXPECT_GT(a.medianErrorPx, supervisor.relocalisation().degradedLimitPx()) << f;
    EXPECT_GT(cameraPositionError(t.cameraToCT, s.poses[f]), 1.0) << f;
    EXPECT_FALSE(c.searched) << f;
  }
}

TEST(TrackingSupervisor, FindsTheScopeThatMovedOnWhileTheFrameWasBlank)
{
  // Frame 8 is black and the scope moves on faster than predicted: the next
  // frame seen is frame 12, which is lost; its features are cast from the
  // prediction, which is wrong. After two frames followed so (the sequence
  // is short: 2, not the default 3), whose contours lie far from the
  // model's, the supervisor searches for the last one's pose against the
  // CT and moves the tracker there; the next frame's contours confirm it
  // (anchored).
  const fixtures::Sequence& s = fixtures::sequence();
  const FrameContourCheck check(*s.model, s.intrinsics, cv::Mat());
  ContourRelocalisationOptions afterTwo;
  afterTwo.triggerFrames = 2;
  TrackingSupervisor supervisor(check, ContourWindowRefinementOptions(), true, afterTwo, 0.0);
  EndoscopeTracker tracker(s.mesh, s.intrinsics);
  tracker.start(s.frames[0], s.poses[0]);
  const cv::Mat black = cv::Mat::zeros(s.frames[0].size(), s.frames[0].type());
  int relocalisedAt = -1;
  int anchoredAt = -1;
  double predictedMm = 0.0;
  for (std::size_t f = 1; f < s.frames.size(); ++f)
  {
    if (f >= 9 && f <= 11)
    {
      continue;
    }
    TrackedFrame t = tracker.track(f == 8 ? black : s.frames[f]);
    const FrameContourAgreement a = supervisor.judge(f == 8 ? black : s.frames[f], t);
    const CheckedTrackedFrame c = supervisor.follow(tracker, t, a);
    const double mm = cameraPositionError(t.cameraToCT, s.poses[f]);
    std::printf("frame %2zu: %s (%s), %.2f px, %.3f mm%s%s\n", f, toString(t.state),
      t.reason.c_str(), a.medianErrorPx, mm,
      c.relocalised  ? ", relocalised"
        : c.searched ? ", searched"
                     : "",
      c.anchored ? ", anchored" : "");
    if (c.searched)
    {
      std::printf("  search: %.2f px at the tracked pose, %.2f px at best, %.0f ms\n",
        c.searchTrackedErrorPx, c.searchBestErrorPx, c.searchMs);
      EXPECT_GT(c.searchMs, 0.0);
    }
    if (f == 12)
    {
      predictedMm = mm;
    }
    // One frame's contours find the pose within half a millimetre (the
    // refinement then takes it further).
    if (relocalisedAt >= 0)
    {
      EXPECT_LT(mm, 0.5) << f;
    }
    if (c.relocalised && relocalisedAt < 0)
    {
      relocalisedAt = static_cast<int>(f);
      EXPECT_LT(cameraPositionError(*c.corrected, s.poses[f]), 0.5) << f;
    }
    if (c.anchored && f > 8 && anchoredAt < 0)
    {
      anchoredAt = static_cast<int>(f);
    }
  }
  EXPECT_GT(predictedMm, 0.5);
  EXPECT_EQ(relocalisedAt, 14);
  EXPECT_EQ(anchoredAt, 15);
}

TEST(TrackingSupervisor, AnchorsTheTrackerAgainAfterABlankFrame)
{
  // Frame 8 is black: it and the next are lost, and the frames after would
  // be followed from features cast from the prediction (degraded,
  // unanchored). The supervisor finds the pose against the CT and anchors
  // the tracker within a few frames: from then the frames are tracking.
  const fixtures::Sequence& s = fixtures::sequence();
  const FrameContourCheck check(*s.model, s.intrinsics, cv::Mat());
  TrackingSupervisor supervisor(check, ContourWindowRefinementOptions(), true, {}, 0.0);
  EndoscopeTracker tracker(s.mesh, s.intrinsics);
  tracker.start(s.frames[0], s.poses[0]);
  const cv::Mat black = cv::Mat::zeros(s.frames[0].size(), s.frames[0].type());
  int anchoredAt = -1;
  for (std::size_t f = 1; f < s.frames.size(); ++f)
  {
    TrackedFrame t = tracker.track(f == 8 ? black : s.frames[f]);
    const FrameContourAgreement a = supervisor.judge(f == 8 ? black : s.frames[f], t);
    const CheckedTrackedFrame c = supervisor.follow(tracker, t, a);
    const double mm = cameraPositionError(t.cameraToCT, s.poses[f]);
    std::printf("frame %2zu: %s (%s), %.2f px, %.3f mm%s\n", f, toString(t.state), t.reason.c_str(),
      a.medianErrorPx, mm,
      c.relocalised  ? ", relocalised"
        : c.searched ? ", searched"
                     : "");
    EXPECT_LT(mm, 0.5) << f;
    if (f < 8)
    {
      EXPECT_EQ(t.state, TrackingState::Tracking) << f;
    }
    else if (anchoredAt < 0)
    {
      EXPECT_NE(t.state, TrackingState::Tracking) << f;
      anchoredAt = c.anchored ? static_cast<int>(f) : -1;
    }
    else
    {
      EXPECT_EQ(t.state, TrackingState::Tracking) << f;
      EXPECT_TRUE(t.anchored) << f;
    }
  }
  EXPECT_GT(anchoredAt, 0);
  EXPECT_LE(anchoredAt, 12);
}

TEST(TrackingSupervisor, DoesNotLetContoursAnchorATrackerLostLongerThanItsPredictionCoasts)
{
  // Six black frames after frame 7 (more than the 5 the prediction coasts):
  // whatever the contours say afterwards, the tracker stays unanchored and
  // its frames degraded, since one frame's contours also fit poses far off.
  const fixtures::Sequence& s = fixtures::sequence();
  const FrameContourCheck check(*s.model, s.intrinsics, cv::Mat());
  TrackingSupervisor supervisor(check, ContourWindowRefinementOptions(), true, {}, 0.0);
  EndoscopeTracker tracker(s.mesh, s.intrinsics);
  ASSERT_EQ(tracker.options().maxCoastFrames, 5);
  tracker.start(s.frames[0], s.poses[0]);
  const cv::Mat black = cv::Mat::zeros(s.frames[0].size(), s.frames[0].type());
  std::vector<cv::Mat> frames(s.frames.begin() + 1, s.frames.begin() + 8);
  frames.insert(frames.end(), 6, black);
  frames.insert(frames.end(), s.frames.begin() + 8, s.frames.end());
  int degradedAfter = 0;
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    TrackedFrame t = tracker.track(frames[i]);
    const FrameContourAgreement a = supervisor.judge(frames[i], t);
    const CheckedTrackedFrame c = supervisor.follow(tracker, t, a);
    std::printf("input %2zu: %s (%s), %.2f px%s\n", i, toString(t.state), t.reason.c_str(),
      a.medianErrorPx, c.anchored ? ", anchored" : "");
    if (i >= 7 + 6 + 1)
    {
      EXPECT_FALSE(c.anchored) << i;
      EXPECT_NE(t.state, TrackingState::Tracking) << i;
      degradedAfter += t.state == TrackingState::Degraded ? 1 : 0;
    }
  }
  EXPECT_GE(degradedAfter, 5);
}

/// The first input frame after three black ones (the scope held at frame
/// 7) at which the supervisor anchors the tracker again, given the
/// electromagnetic tracker's tip at every frame: the true optical centre
/// moved `offsetMm` along the camera's x axis. The prediction holds where
/// the scope was lost (maxCoastFrames 0), so that the loss is a long one,
/// after which contours alone anchor nothing. With `turnDeg`, the tracker
/// has a rotation too: the true one turned by that about the view axis,
/// from the second frame after the stretch on (so that the first one's
/// features are cast as with the tip alone, and the pose found is the
/// same). The tracker's error is learned over `learnFrames` (0: it is
/// taken as it reads), shrunk as if `priorFrames` had seen none. -1 when it
/// never anchors.
int anchoredAfterALongLossWithTheTip(double offsetMm, std::optional<double> turnDeg = std::nullopt,
  int learnFrames = EndoscopeTrackerOptions().trackerOffsetFrames,
  int priorFrames = EndoscopeTrackerOptions().trackerOffsetPriorFrames)
{
  const fixtures::Sequence& s = fixtures::sequence();
  const FrameContourCheck check(*s.model, s.intrinsics, cv::Mat());
  TrackingSupervisor supervisor(check, ContourWindowRefinementOptions(), true, {}, 0.0);
  EndoscopeTrackerOptions holding;
  holding.maxCoastFrames = 0;
  holding.trackerOffsetFrames = learnFrames;
  holding.trackerOffsetPriorFrames = priorFrames;
  EndoscopeTracker tracker(s.mesh, s.intrinsics, holding);
  tracker.start(s.frames[0], s.poses[0]);
  const cv::Mat black = cv::Mat::zeros(s.frames[0].size(), s.frames[0].type());
  const int blackFrames = 3;
  std::vector<cv::Mat> frames(s.frames.begin() + 1, s.frames.begin() + 8);
  std::vector<CameraPose> truth(s.poses.begin() + 1, s.poses.begin() + 8);
  frames.insert(frames.end(), blackFrames, black);
  truth.insert(truth.end(), blackFrames, s.poses[7]);
  frames.insert(frames.end(), s.frames.begin() + 8, s.frames.end());
  truth.insert(truth.end(), s.poses.begin() + 8, s.poses.end());
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    TrackerPrior prior(truth[i].centre + offsetMm * truth[i].rotation.col(0));
    if (turnDeg && i > 7 + blackFrames)
    {
      prior.rotationCT =
        Eigen::AngleAxisd(*turnDeg * M_PI / 180.0, truth[i].rotation.col(2)).toRotationMatrix() *
        truth[i].rotation;
    }
    TrackedFrame t = tracker.track(frames[i], prior);
    const FrameContourAgreement a = supervisor.judge(frames[i], t);
    const CheckedTrackedFrame c = supervisor.follow(tracker, t, a);
    std::printf("input %2zu: %s (%s), %.2f px, %.2f mm from the tip, turned %.2f deg from the "
                "tracker%s\n",
      i, toString(t.state), t.reason.c_str(), a.medianErrorPx, t.tipDistanceMm.value_or(-1.0),
      t.trackerTurnDeg.value_or(-1.0), c.anchored ? ", anchored" : "");
    if (i >= 7 + blackFrames && c.anchored)
    {
      EXPECT_LT(cameraPositionError(t.cameraToCT, truth[i]), 0.5) << i;
      return static_cast<int>(i);
    }
  }
  return -1;
}

TEST(TrackingSupervisor, LetsContoursAnchorATrackerAfterALongLossWhereTheTrackersTipAgrees)
{
  // With the electromagnetic tracker's tip at the true centre, a pose within
  // 1 mm of it whose contours agree is anchored again after the loss. With
  // the tip 2 mm off (a poorly registered tracker: near enough not to
  // degrade the poses, too far to confirm one) taken as it reads, the
  // tracker stays unanchored, as without a tracker; so it does when the 7
  // tracked frames before the loss are all that measured its error (shrunk
  // as if 30 frames had seen none, 0.38 mm of the 2 are taken off). When
  // those frames are taken as enough (no shrinkage), the corrected tip
  // confirms the pose as the exact one does (and the pose is within 0.5 mm
  // of the truth: anchoredAfterALongLossWithTheTip() checks).
  const int withTip = anchoredAfterALongLossWithTheTip(0.0);
  EXPECT_GE(withTip, 7 + 3);
  EXPECT_LE(withTip, 7 + 3 + 4);
  EXPECT_EQ(anchoredAfterALongLossWithTheTip(2.0, std::nullopt, 0), -1);
  EXPECT_EQ(anchoredAfterALongLossWithTheTip(2.0), -1);
  const int learned = anchoredAfterALongLossWithTheTip(2.0, std::nullopt, 90, 0);
  EXPECT_GE(learned, 7 + 3);
  EXPECT_LE(learned, 7 + 3 + 4);
}

TEST(TrackingSupervisor,
  LetsContoursAnchorATrackerAfterALongLossOnlyWhereASixDofTrackersRotationAgrees)
{
  // A 6-DOF tracker at the true pose anchors as the tip does; one whose
  // rotation is 3 degrees off the pose found (within the 5 that degrade a
  // pose, beyond the 2 that confirm one) keeps the tracker unanchored,
  // although the pose is the same and the contours agree with it. (Its
  // rotation comes only after the loss, so no tracked frame has measured
  // its error: the pose is not pulled towards it, which would make them
  // agree.)
  const int withPose = anchoredAfterALongLossWithTheTip(0.0, 0.0);
  EXPECT_GE(withPose, 7 + 3);
  EXPECT_LE(withPose, 7 + 3 + 4);
  EXPECT_EQ(anchoredAfterALongLossWithTheTip(0.0, 3.0), -1);
}

} // namespace
} // namespace vimlop
