#include <vimlop/Core/MethodDescriptor.h>

#include <gtest/gtest.h>

using namespace vimlop;

TEST(MethodDescriptor, VIMLOPUsesEveryStage)
{
  const MethodDescriptor d = describeMethod(RegistrationMethod::VIMLOP);
  EXPECT_TRUE(d.usesContours);
  EXPECT_EQ(d.pointMatching, PointMatching::MostLikelyPoint);
  EXPECT_TRUE(d.chiSquareTest);
  EXPECT_EQ(d.trimming, TrimSchedule::FirstStageOnly);
  EXPECT_TRUE(d.anatomicalConstraint);
  EXPECT_EQ(d.poseEstimation, PoseEstimation::LevenbergMarquardt);
}

TEST(MethodDescriptor, IMLPIsVIMLOPWithoutContours)
{
  const MethodDescriptor d = describeMethod(RegistrationMethod::IMLP);
  EXPECT_FALSE(d.usesContours);
  EXPECT_EQ(d.pointMatching, PointMatching::MostLikelyPoint);
  EXPECT_TRUE(d.chiSquareTest);
  EXPECT_EQ(d.trimming, TrimSchedule::FirstStageOnly);
  EXPECT_TRUE(d.anatomicalConstraint);
  EXPECT_EQ(d.poseEstimation, PoseEstimation::LevenbergMarquardt);
}

TEST(MethodDescriptor, TrimmedICPIsEuclideanClosedFormAndUnconstrained)
{
  const MethodDescriptor d = describeMethod(RegistrationMethod::TrimmedICP);
  EXPECT_FALSE(d.usesContours);
  EXPECT_EQ(d.pointMatching, PointMatching::ClosestPoint);
  EXPECT_FALSE(d.chiSquareTest);
  EXPECT_EQ(d.trimming, TrimSchedule::Throughout);
  EXPECT_FALSE(d.anatomicalConstraint);
  EXPECT_EQ(d.poseEstimation, PoseEstimation::ClosedFormSimilarity);
}

TEST(MethodDescriptor, TheConstraintNeedsTheMethodAndTheOption)
{
  RegistrationOptions o;
  EXPECT_TRUE(usesAnatomicalConstraint(o));
  o.anatomicalConstraint = false;
  EXPECT_FALSE(usesAnatomicalConstraint(o));
  o.anatomicalConstraint = true;
  o.method = RegistrationMethod::TrimmedICP;
  EXPECT_FALSE(usesAnatomicalConstraint(o));
}

TEST(MethodDescriptor, AnUnknownMethodGetsAClearError)
{
  try
  {
    describeMethod(static_cast<RegistrationMethod>(7));
    ADD_FAILURE() << "no error";
  }
  catch (const std::exception& e)
  {
    EXPECT_EQ(std::string(e.what()), "registration: unknown method 7");
  }
}
