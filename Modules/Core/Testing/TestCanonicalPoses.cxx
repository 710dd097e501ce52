#include "TestMeshes.h"
#include <vimlop/Core/CanonicalPoses.h>
#include <vimlop/Core/Error.h>

#include <gtest/gtest.h>

using namespace vimlop;

namespace
{

const RegistrationModel& tubeModel()
{
  // A passage of radius about 4 mm along z from 0 to 60 mm.
  static const RegistrationModel model(fixtures::makeTube(4.0, 60.0, 0.1));
  return model;
}

} // namespace

TEST(CanonicalPoses, FollowThePassageLookingAlongIt)
{
  CanonicalPoseOptions options;
  options.upCT = Eigen::Vector3d::UnitX();
  const std::vector<CameraPose> poses = makeCanonicalPoses(tubeModel(), options);
  ASSERT_GE(poses.size(), 20u);
  for (const CameraPose& pose : poses)
  {
    EXPECT_TRUE(tubeModel().isInside(pose.centre));
    // On the centre line, where the wall is farthest.
    EXPECT_LT(pose.centre.head<2>().norm(), 1.6) << pose.centre.transpose();
    // Along the passage, with the image up towards +x (away from the capped
    // ends, where the look-ahead meets the cap and tilts the view).
    if (pose.centre.z() > 12.0 && pose.centre.z() < 48.0)
    {
      EXPECT_GT(std::abs(pose.viewDirection().z()), 0.98)
        << pose.centre.transpose() << " | " << pose.viewDirection().transpose();
    }
    EXPECT_GT(-pose.rotation.col(1).x(), 0.9);
  }
  // Both ways along the passage, positions at least the spacing apart.
  int forward = 0;
  for (size_t i = 0; i < poses.size(); ++i)
  {
    forward += poses[i].viewDirection().z() > 0.0;
    for (size_t j = 0; j < i; ++j)
    {
      const double d = (poses[i].centre - poses[j].centre).norm();
      EXPECT_TRUE(d < 1e-9 || d >= options.spacingMm - 1e-9) << d;
    }
  }
  EXPECT_GT(forward, 5);
  EXPECT_LT(forward, static_cast<int>(poses.size()) - 5);
}

TEST(CanonicalPoses, RollsAndBoundsAndDeterminism)
{
  CanonicalPoseOptions options;
  options.rollsDeg = { -20.0, 0.0, 20.0 };
  options.viewsPerPosition = 1;
  options.threads = 2;
  const std::vector<CameraPose> poses = makeCanonicalPoses(tubeModel(), options);
  ASSERT_EQ(poses.size() % 3, 0u);
  // The three rolls of a view share its centre and axis, 20 degrees apart.
  const CameraPose& a = poses[0];
  const CameraPose& b = poses[1];
  EXPECT_EQ(a.centre, b.centre);
  EXPECT_NEAR(a.viewDirection().dot(b.viewDirection()), 1.0, 1e-12);
  EXPECT_NEAR(std::acos(a.rotation.col(0).dot(b.rotation.col(0))) * 180.0 / M_PI, 20.0, 1e-6);
  // Looking along +z or -z with up +z: the anterior (-y) is up instead.
  EXPECT_GT(-b.rotation.col(1).dot(-Eigen::Vector3d::UnitY()), 0.99);

  // The deepest first: a bound keeps the first poses. One thread gives the
  // same poses as two.
  options.maxPoses = 7;
  const std::vector<CameraPose> first = makeCanonicalPoses(tubeModel(), options);
  ASSERT_EQ(first.size(), 7u);
  EXPECT_EQ(first[6].matrix(), poses[6].matrix());
  options.maxPoses = 20000;
  options.threads = 1;
  const std::vector<CameraPose> again = makeCanonicalPoses(tubeModel(), options);
  ASSERT_EQ(again.size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i)
  {
    EXPECT_EQ(again[i].matrix(), poses[i].matrix());
  }
}

TEST(CanonicalPoses, BadOptionsAndNarrowAirwaysGetClearErrors)
{
  CanonicalPoseOptions options;
  options.spacingMm = 0.0;
  EXPECT_THROW(makeCanonicalPoses(tubeModel(), options), Error);
  options = CanonicalPoseOptions();
  options.rollsDeg.clear();
  EXPECT_THROW(makeCanonicalPoses(tubeModel(), options), Error);
  options = CanonicalPoseOptions();
  options.threads = -1;
  try
  {
    makeCanonicalPoses(tubeModel(), options);
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("thread count must not be negative"), std::string::npos)
      << e.what();
  }
  options = CanonicalPoseOptions();
  options.minClearanceMm = 10.0; // wider than the tube
  try
  {
    makeCanonicalPoses(tubeModel(), options);
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("mm from the wall"), std::string::npos) << e.what();
  }
}
