#include <vimlop/Core/Error.h>
#include <vimlop/Core/NoiseModel.h>
#include <vimlop/Core/RegistrationData.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>

using namespace vimlop;

TEST(NoiseModel, ViewAlignedHasTheRightStdAlongAndAcross)
{
  const Eigen::Vector3d v = Eigen::Vector3d(1.0, 2.0, -2.0); // length 3
  const Eigen::Matrix3d c = viewAlignedCovariance(v, 0.5, 0.3);
  const Eigen::Vector3d u = v.normalized();
  EXPECT_NEAR(u.dot(c * u), 0.25, 1e-12);
  const Eigen::Vector3d across = u.cross(Eigen::Vector3d::UnitX()).normalized();
  EXPECT_NEAR(across.dot(c * across), 0.09, 1e-12);
  EXPECT_NEAR(across.dot(c * u), 0.0, 1e-12);
  EXPECT_EQ(covarianceProblem(c), "");
  EXPECT_NEAR(isotropicCovariance(0.5).trace(), 0.75, 1e-15);
  EXPECT_THROW(viewAlignedCovariance(Eigen::Vector3d::Zero(), 0.5, 0.3), Error);
}

TEST(NoiseModel, CovarianceProblemsAreNamed)
{
  Eigen::Matrix3d c = Eigen::Matrix3d::Identity();
  c(0, 1) = 0.5;
  EXPECT_EQ(covarianceProblem(c), "is not symmetric");
  c = Eigen::Matrix3d::Identity();
  c(2, 2) = -1.0;
  EXPECT_EQ(covarianceProblem(c), "is not positive definite");
  c(2, 2) = std::nan("");
  EXPECT_EQ(covarianceProblem(c), "has non-finite entries");
  EXPECT_STREQ(toString(PointNoiseModel::ViewAligned), "view-aligned");
}

TEST(RegistrationData, ValidateNamesTheProblem)
{
  auto message = [](const RegistrationData& d)
  {
    try
    {
      d.validate();
    }
    catch (const Error& e)
    {
      return std::string(e.what());
    }
    return std::string("valid");
  };
  RegistrationData data;
  EXPECT_EQ(message(data), "registration data: the point set is empty");
  data.points = { { 0, 0, 0 }, { 1, 0, 0 } };
  data.pointCovariances = { Eigen::Matrix3d::Identity() };
  EXPECT_EQ(message(data), "registration data: 1 covariances for 2 points");
  data.pointCovariances.push_back(Eigen::Matrix3d::Identity());
  EXPECT_EQ(message(data), "valid");
  data.points[1].y() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(message(data), "registration data: point 1 is NaN or infinite");
  data.points[1].y() = 0.0;
  data.pointCovariances[0](1, 1) = 0.0;
  EXPECT_EQ(message(data), "registration data: the covariance of point 0 is not positive definite");
  data.pointCovariances[0] = Eigen::Matrix3d::Identity();

  VideoFrame frame;
  frame.frameId = 7;
  frame.intrinsics.fx = frame.intrinsics.fy = 100;
  frame.intrinsics.cx = 50;
  frame.intrinsics.cy = 40;
  frame.intrinsics.widthPx = 100;
  frame.intrinsics.heightPx = 80;
  frame.contour.push_back({ { 10, 10 }, { 0.6, 0.8 } });
  data.frames.push_back(frame);
  EXPECT_EQ(message(data), "valid");
  EXPECT_EQ(data.numberOfContourPoints(), 1);
  data.frames[0].contour[0].normal = { 1.0, 1.0 };
  EXPECT_EQ(message(data),
    "registration data: frame 7: the normal of contour point 0 is not a unit vector");
  data.frames[0].contour[0].normal = { 1.0, 0.0 };
  data.frames[0].intrinsics.fx = -1;
  EXPECT_EQ(
    message(data), "registration data: frame 7: focal lengths must be positive (fx=-1, fy=100)");
}
