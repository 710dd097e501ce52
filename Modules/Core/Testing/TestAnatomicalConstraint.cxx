#include "TestMeshes.h"
#include <vimlop/Core/AnatomicalConstraint.h>

#include <gtest/gtest.h>

using namespace vimlop;

namespace
{

/// A spherical cavity of radius 10 mm about the origin.
const RegistrationModel& cavity()
{
  static const RegistrationModel model(fixtures::makeSphere(10.0, 3));
  return model;
}

std::vector<VideoFrame> framesAt(const std::vector<Eigen::Vector3d>& centresSfm)
{
  std::vector<VideoFrame> frames;
  for (size_t j = 0; j < centresSfm.size(); ++j)
  {
    VideoFrame frame;
    frame.frameId = 100 + static_cast<int>(j);
    frame.cameraToSfm.centre = centresSfm[j];
    frames.push_back(frame);
  }
  return frames;
}

SimilarityTransform shift(double xMm)
{
  SimilarityTransform T;
  T.translation = Eigen::Vector3d(xMm, 0.0, 0.0);
  return T;
}

} // namespace

TEST(AnatomicalConstraint, CamerasInsideNamesTheFirstFrameOutside)
{
  const std::vector<VideoFrame> frames = framesAt({ { 0, 0, 0 }, { 6, 0, 0 }, { 8, 0, 0 } });
  int outside = -1;
  EXPECT_TRUE(camerasInside(cavity(), frames, SimilarityTransform(), &outside));
  EXPECT_EQ(outside, -1);
  // Shifted by 3 mm the last camera (at 11 mm) leaves; by 5 mm the middle one too.
  EXPECT_FALSE(camerasInside(cavity(), frames, shift(3.0), &outside));
  EXPECT_EQ(outside, 102);
  EXPECT_FALSE(camerasInside(cavity(), frames, shift(5.0), &outside));
  EXPECT_EQ(outside, 101);
  // The scale of T moves the cameras too.
  SimilarityTransform grow;
  grow.scale = 1.3;
  EXPECT_FALSE(camerasInside(cavity(), frames, grow));
  EXPECT_TRUE(camerasInside(cavity(), {}, shift(50.0)));
}

TEST(AnatomicalConstraint, BackOffHalvesTheChangeUntilEveryCameraIsInside)
{
  const std::vector<VideoFrame> frames = framesAt({ { 0, 0, 0 } });
  int steps = -1;
  const SimilarityTransform kept =
    backOffIntoAirway(cavity(), frames, SimilarityTransform(), shift(4.0), 10, steps);
  EXPECT_EQ(steps, 0);
  EXPECT_NEAR(kept.translation.x(), 4.0, 1e-12);

  const SimilarityTransform half =
    backOffIntoAirway(cavity(), frames, SimilarityTransform(), shift(15.0), 10, steps);
  EXPECT_EQ(steps, 1);
  EXPECT_NEAR(half.translation.x(), 7.5, 1e-9);

  // 1000 mm / 2^7 = 7.8 mm is the first fraction inside the 10 mm cavity.
  const SimilarityTransform far =
    backOffIntoAirway(cavity(), frames, shift(1.0), shift(1000.0), 10, steps);
  EXPECT_EQ(steps, 7);
  EXPECT_NEAR(far.translation.x(), 1.0 + 999.0 / 128.0, 1e-9);
}

TEST(AnatomicalConstraint, BackOffUndoesAnUpdateItCannotRescue)
{
  const std::vector<VideoFrame> frames = framesAt({ { 0, 0, 0 } });
  int steps = -1;
  const SimilarityTransform undone =
    backOffIntoAirway(cavity(), frames, shift(2.0), shift(1000.0), 3, steps);
  EXPECT_EQ(steps, 4);
  EXPECT_NEAR(undone.translation.x(), 2.0, 1e-12);
}
