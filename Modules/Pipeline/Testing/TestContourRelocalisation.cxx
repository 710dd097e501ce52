#include <vimlop/Pipeline/ContourRelocalisation.h>

#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/VisibleModelContours.h>
#include <vimlop/Pipeline/FrameContourCheck.h>
#include <vimlop/Pipeline/TrackingSupervisor.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include "ErrorMessage.h"
#include "TestMeshes.h"
#include "TubeCameras.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

namespace vimlop
{
namespace
{

/// A frame's contours as a perfect detector finds them: each visible model
/// contour sample where the true camera sees it.
std::vector<ContourPoint> trueContours(
  const RegistrationModel& model, const PinholeCamera& k, const CameraPose& truth)
{
  std::vector<ContourPoint> contours;
  for (const ModelContourPoint& p : visibleModelContours(model, k, truth))
  {
    contours.push_back({ p.pixel, p.pixelNormal });
  }
  return contours;
}

/// The same rigid move of every camera: turned by `turnDeg` about the last
/// camera's own y axis through its centre, and shifted by `shiftMm` along
/// its own x axis.
std::vector<RelocalisationFrame> drifted(const RegistrationModel& model, const PinholeCamera& k,
  const std::vector<CameraPose>& truth, double shiftMm, double turnDeg)
{
  const CameraPose& last = truth.back();
  const Eigen::Matrix3d turn = last.rotation *
    Eigen::AngleAxisd(turnDeg * M_PI / 180.0, Eigen::Vector3d::UnitY()).matrix() *
    last.rotation.transpose();
  std::vector<RelocalisationFrame> window;
  for (const CameraPose& pose : truth)
  {
    CameraPose off;
    off.rotation = turn * pose.rotation;
    off.centre = last.centre + turn * (pose.centre - last.centre) + last.rotation.col(0) * shiftMm;
    window.push_back({ trueContours(model, k, pose), off });
  }
  return window;
}

TEST(ContourRelocalisation, BringsTheWindowBackFromAShiftAndATurnThatDriftedItOff)
{
  // Three frames tracked 1.5 mm aside and 4 degrees turned (a tracker that
  // drifted, or was cast wrong after a loss): the search lays their contours
  // back on the model's, near the true poses.
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeTube(4.0, 60.0, 0.35));
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  const FrameContourCheck check(model, k, cv::Mat());
  const std::vector<CameraPose> truth = fixtures::camerasAlongTheTube(3, 2);
  const std::vector<RelocalisationFrame> window = drifted(model, k, truth, 1.5, 4.0);
  const RelocalisationResult r = relocaliseAgainstCT(check, window, {});
  EXPECT_EQ(r.starts, 13);
  ASSERT_TRUE(r.correction.has_value())
    << r.trackedErrorPx << " px tracked, " << r.bestErrorPx << " px at best";
  EXPECT_GT(r.trackedErrorPx, 5.0);
  EXPECT_LT(r.bestErrorPx, 0.5);
  const CameraPose found = r.correction->apply(window.back().cameraToCT);
  EXPECT_LT(cameraPositionError(found, truth.back()), 0.3);
  EXPECT_LT(cameraAngleErrorDeg(found, truth.back()), 0.5);
}

TEST(ContourRelocalisation, FindsNothingWhereNoPoseWithinItsSearchFitsTheContours)
{
  // The contours of cameras 15 mm farther down the tube than their tracked
  // poses: no pose within twice the search (4 mm, 10 degrees) fits them.
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeTube(4.0, 60.0, 0.35));
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  const FrameContourCheck check(model, k, cv::Mat());
  const std::vector<CameraPose> seen = fixtures::camerasAlongTheTube(3, 12);
  const std::vector<CameraPose> tracked = fixtures::camerasAlongTheTube(3, 2);
  std::vector<RelocalisationFrame> window;
  for (std::size_t i = 0; i < seen.size(); ++i)
  {
    window.push_back({ trueContours(model, k, seen[i]), tracked[i] });
  }
  const RelocalisationResult r = relocaliseAgainstCT(check, window, {});
  EXPECT_FALSE(r.correction.has_value()) << r.bestErrorPx << " px at best";
  EXPECT_GT(r.bestErrorPx, ContourRelocalisationOptions().acceptLimitPx());
}

TEST(ContourRelocalisation, AcceptsAsMuchMoreErrorAsTheRegistrationLeft)
{
  // Where the model is not the anatomy, the contours disagree with it at the
  // truth by as much as the registration left: the limits follow it.
  ContourRelocalisationOptions o;
  EXPECT_DOUBLE_EQ(o.degradedLimitPx(), 6.0);
  EXPECT_DOUBLE_EQ(o.acceptLimitPx(), 2.0);
  o.registeredErrorPx = 10.0;
  EXPECT_DOUBLE_EQ(o.degradedLimitPx(), 40.0);
  EXPECT_DOUBLE_EQ(o.acceptLimitPx(), 15.0);
}

TEST(ContourRelocalisation, RefusesSettingsOutOfRangeAndAnEmptyWindow)
{
  const auto messageOf = [](auto change)
  {
    ContourRelocalisationOptions o;
    change(o);
    return fixtures::errorMessageOf([&] { o.validate(); });
  };
  EXPECT_EQ(messageOf([](ContourRelocalisationOptions& o) { o.degradedAbovePx = 0.0; }),
    "relocalisation: the contour error of an untrusted frame must be positive (px, times the "
    "registration's), not 0");
  EXPECT_EQ(messageOf([](ContourRelocalisationOptions& o) { o.triggerFrames = 0; }),
    "relocalisation: at least 1 unanchored frame must trigger a search, not 0");
  EXPECT_EQ(messageOf([](ContourRelocalisationOptions& o) { o.searchDeg = -1.0; }),
    "relocalisation: the search must reach a positive distance and angle (mm, degrees), not -1");
  EXPECT_EQ(messageOf([](ContourRelocalisationOptions& o) { o.retryFrames = 0; }),
    "relocalisation: at least 1 frame must pass between searches, not 0");
  EXPECT_EQ(messageOf([](ContourRelocalisationOptions& o) { o.iterations = 0; }),
    "relocalisation: each start needs at least 1 iteration, not 0");
  EXPECT_EQ(messageOf([](ContourRelocalisationOptions& o) { o.acceptPx = 0.0; }),
    "relocalisation: the accepted contour error must be positive (px, times the "
    "registration's), not 0");
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeTube(4.0, 60.0, 0.35));
  const FrameContourCheck check(model, PinholeCamera::simulatedEndoscope(), cv::Mat());
  EXPECT_EQ(fixtures::errorMessageOf([&] { relocaliseAgainstCT(check, {}, {}); }),
    "relocalisation: no frames to relocalise");
}

TEST(TrackingSupervisor, FollowsOnlyAFrameItJudged)
{
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeTube(4.0, 60.0, 0.35));
  const FrameContourCheck check(model, PinholeCamera::simulatedEndoscope(), cv::Mat());
  TrackingSupervisor supervisor(check, std::nullopt, true, {}, 0.0);
  EndoscopeTracker tracker(model.mesh(), PinholeCamera::simulatedEndoscope());
  EXPECT_EQ(fixtures::errorMessageOf([&] { supervisor.follow(tracker, TrackedFrame(), {}); }),
    "tracking supervisor: follow() a frame that judge() checked");
  ContourRelocalisationOptions wrong;
  wrong.windowFrames = 0;
  EXPECT_EQ(
    fixtures::errorMessageOf([&] { TrackingSupervisor(check, std::nullopt, true, wrong, 0.0); }),
    "relocalisation: the window needs at least 1 frame, not 0");
}

} // namespace
} // namespace vimlop
