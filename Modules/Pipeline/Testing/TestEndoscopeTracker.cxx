#include <vimlop/Pipeline/EndoscopeTracker.h>

#include "ErrorMessage.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

namespace vimlop
{
namespace
{

TEST(EndoscopeTracker, RefusesFramesOfAnotherSizeAndTrackingBeforeItStarted)
{
  EndoscopeTracker tracker(
    fixtures::makeTube(4.0, 60.0, 0.35), PinholeCamera::simulatedEndoscope());
  const cv::Mat frame(240, 320, CV_8UC3, cv::Scalar(90, 90, 160));
  EXPECT_EQ(fixtures::errorMessageOf([&] { tracker.track(frame); }),
    "endoscope tracker: start() on a registered frame first");
  EXPECT_EQ(
    fixtures::errorMessageOf([&] { tracker.correct(fixtures::cameraOnTheTubeAxis(), true); }),
    "endoscope tracker: start() on a registered frame first");
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] { tracker.start(cv::Mat(480, 640, CV_8UC3), fixtures::cameraOnTheTubeAxis()); }),
    "endoscope tracker: a frame of 640 x 480 pixels, but the intrinsics are for 320 x 240");
}

TEST(EndoscopeTracker, RefusesToStartOnAFrameWithoutTexture)
{
  // A flat frame has no corners: there is nothing to follow.
  EndoscopeTracker tracker(
    fixtures::makeTube(4.0, 60.0, 0.35), PinholeCamera::simulatedEndoscope());
  const cv::Mat flat(240, 320, CV_8UC3, cv::Scalar(90, 90, 160));
  EXPECT_EQ(fixtures::errorMessageOf([&] { tracker.start(flat, fixtures::cameraOnTheTubeAxis()); }),
    "endoscope tracker: only 0 corners of the first frame stand for a point of the model (at "
    "least 25 needed): is the camera inside the airway, and the frame textured?");
}

TEST(EndoscopeTracker, NamesEachStateAndRefusesOptionsOutOfRange)
{
  EXPECT_STREQ(toString(TrackingState::Tracking), "tracking");
  EXPECT_STREQ(toString(TrackingState::Degraded), "degraded");
  EXPECT_STREQ(toString(TrackingState::Lost), "lost");
  const TriangleMesh tube = fixtures::makeTube(4.0, 60.0, 0.35);
  auto refusal = [&](const EndoscopeTrackerOptions& o)
  {
    return fixtures::errorMessageOf(
      [&] { EndoscopeTracker t(tube, PinholeCamera::simulatedEndoscope(), o); });
  };
  EndoscopeTrackerOptions o;
  o.redetectBelow = 400;
  EXPECT_EQ(refusal(o),
    "endoscope tracker: new corners must be sought below a count in [0, the most features], not "
    "400");
  o = {};
  o.minInliers = 3;
  EXPECT_EQ(refusal(o), "endoscope tracker: a pose needs at least 6 inliers, not 3");
  o = {};
  o.minIncidenceCosine = 1.0;
  EXPECT_EQ(refusal(o), "endoscope tracker: the least incidence cosine must lie in [0, 1), not 1");
  o = {};
  o.maxTipDistanceMm = 0.0;
  EXPECT_EQ(refusal(o),
    "endoscope tracker: the largest distance from the tracker's tip must be positive (mm), not 0");
  o = {};
  o.maxTrackerTurnDeg = -1.0;
  EXPECT_EQ(refusal(o),
    "endoscope tracker: the largest turn from the tracker's rotation must be "
    "positive (degrees), not -1");
  o = {};
  o.recastFromTrackerAfterFrames = -1;
  EXPECT_EQ(refusal(o),
    "endoscope tracker: the frames before features are cast from the "
    "tracker's pose must not be negative, not -1");
  o = {};
  o.trackerOffsetFrames = -2;
  EXPECT_EQ(refusal(o),
    "endoscope tracker: the frames the tracker's offset is learned over must not be negative, "
    "not -2");
  o = {};
  o.trackerOffsetPriorFrames = -1;
  EXPECT_EQ(refusal(o),
    "endoscope tracker: the tracker's offset prior frames must not be negative, not -1");
  o = {};
  o.trackerPull = 1.5;
  EXPECT_EQ(refusal(o),
    "endoscope tracker: the pull towards the tracker's pose must lie in [0, 1], not 1.5");
  o = {};
  o.features.windowPx = 4;
  EXPECT_EQ(
    refusal(o), "feature tracking: the window must be an odd number of pixels, at least 5, not 4");
  PinholeCamera noSize = PinholeCamera::simulatedEndoscope();
  noSize.widthPx = 0;
  EXPECT_NE(fixtures::errorMessageOf([&] { EndoscopeTracker t(tube, noSize); }), "no error");
}

} // namespace
} // namespace vimlop
