#include <vimlop/Pipeline/VideoTracking.h>

#include "ErrorMessage.h"

#include <gtest/gtest.h>

#include <limits>

namespace vimlop
{
namespace
{

// The whole run (a result folder, frames, outputs) is tested through the
// command line (vimlop.track.*) and Python (vimlop.python.track-video); here,
// what the controller refuses before it reads anything.

TEST(VideoTracking, RefusesOptionsOutOfRangeBeforeReadingAnything)
{
  VideoTrackingOptions options;
  options.firstFrameIndex = -2;
  EXPECT_EQ(fixtures::errorMessageOf([&] { VideoTracking(options).open({}); }),
    "the first frame index must be >= 0, or -1 for the one after the registered frame, not -2");
  options = {};
  options.videoFps = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(fixtures::errorMessageOf([&] { VideoTracking(options).open({}); }),
    "the tracked video's rate must be a finite number > 0 frames per second, not nan");
  options = {};
  options.tracker.maxFeatures = 5;
  EXPECT_EQ(fixtures::errorMessageOf([&] { VideoTracking(options).open({}); }),
    "endoscope tracker: at least 10 features are needed, not 5");
}

TEST(VideoTracking, NeedsExactlyOneFrameSource)
{
  VideoTrackingInputs inputs;
  inputs.resultFolder = "result";
  EXPECT_EQ(fixtures::errorMessageOf([&] { VideoTracking().open(inputs); }),
    "give exactly one of a frame path and a camera index");
  inputs.framesPath = "frames";
  inputs.cameraIndex = 0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { VideoTracking().open(inputs); }),
    "give exactly one of a frame path and a camera index");
}

TEST(VideoTracking, NeedsTheTrackerAndItsRegistrationToTheCTTogether)
{
  // The tracker records its tip in its own frame: without the navigation
  // system's registration of it to the CT its positions mean nothing here,
  // and that registration without a tracker is a mistake too. Both are
  // refused before anything is read.
  VideoTrackingInputs inputs;
  inputs.resultFolder = "result";
  inputs.framesPath = "frames";
  inputs.trackerPath = "tracker.csv";
  EXPECT_EQ(fixtures::errorMessageOf([&] { VideoTracking().open(inputs); }),
    "a tracker's positions are in its own frame: give the tracker registered to the CT "
    "(--tracker-to-ct) to use them");
  inputs.trackerPath.clear();
  inputs.trackerTransform = "ProbeToTracker";
  EXPECT_EQ(fixtures::errorMessageOf([&] { VideoTracking().open(inputs); }),
    "a tracker's positions are in its own frame: give the tracker registered to the CT "
    "(--tracker-to-ct) to use them");
  inputs.trackerTransform.clear();
  inputs.trackerToCTPath = "TrackerToRAS.tfm";
  EXPECT_EQ(fixtures::errorMessageOf([&] { VideoTracking().open(inputs); }),
    "'TrackerToRAS.tfm': a tracker registered to the CT, but no tracker (--tracker)");
}

TEST(VideoTracking, RunsOnlyAfterOpeningAndReportsNothingBefore)
{
  VideoTracking tracking;
  EXPECT_EQ(
    fixtures::errorMessageOf([&] { tracking.run(); }), "VideoTracking::run() before open()");
  EXPECT_EQ(
    fixtures::errorMessageOf([&] { tracking.start(); }), "VideoTracking::start() before open()");
  EXPECT_TRUE(tracking.frames().empty());
  EXPECT_EQ(tracking.count(TrackingState::Tracking), 0);
  EXPECT_TRUE(tracking.stoppedBy().empty());
  EXPECT_FALSE(tracking.stopRequested());
}

} // namespace
} // namespace vimlop
