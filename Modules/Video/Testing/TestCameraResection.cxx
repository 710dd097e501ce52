#include <vimlop/Video/CameraResection.h>

#include "ErrorMessage.h"
#include <vimlop/Core/RegistrationMetrics.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cstdint>

using namespace vimlop;

namespace
{

/// A camera looking into a folded wall of points 10-30 mm ahead, and where
/// they project; every fifth correspondence is moved by 15 px (an outlier).
struct Scene
{
  CameraPose truth;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> pixels;
  std::vector<bool> outlier;
};

Scene scene()
{
  Scene s;
  s.truth.rotation =
    Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1.0, -0.4).normalized()).toRotationMatrix();
  s.truth.centre = { 5.0, -3.0, 12.0 };
  std::uint32_t state = 3u;
  auto uniform = [&]
  {
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / static_cast<double>(1u << 24);
  };
  for (int i = 0; i < 120; ++i)
  {
    const Eigen::Vector2d pixel(10.0 + 300.0 * uniform(), 10.0 + 220.0 * uniform());
    const double depth = 10.0 + 20.0 * uniform();
    s.points.push_back(
      s.truth.cameraToWorld(PinholeCamera::simulatedEndoscope().backProject(pixel, depth)));
    s.outlier.push_back(i % 5 == 0);
    s.pixels.push_back(
      pixel + (s.outlier.back() ? Eigen::Vector2d(15.0, -9.0) : Eigen::Vector2d::Zero()));
  }
  return s;
}

} // namespace

TEST(CameraResection, FindsThePoseFromPointsWithAFifthOfOutliers)
{
  const Scene s = scene();
  for (ResectionSolver solver : { ResectionSolver::EPnP, ResectionSolver::IterativeFromGuess })
  {
    CameraResectionOptions options;
    options.solver = solver;
    // The guess is 2 mm and 3 degrees off.
    CameraPose guess = s.truth;
    guess.centre += Eigen::Vector3d(1.2, -1.0, 1.2);
    guess.rotation =
      guess.rotation * Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const auto r =
      resectCamera(s.points, s.pixels, PinholeCamera::simulatedEndoscope(), options, &guess);
    ASSERT_TRUE(r);
    EXPECT_LT(cameraPositionError(r->cameraToWorld, s.truth), 1e-6);
    EXPECT_LT(cameraAngleErrorDeg(r->cameraToWorld, s.truth), 1e-6);
    EXPECT_EQ(r->inliers.size(), 96u);
    for (int i : r->inliers)
    {
      EXPECT_FALSE(s.outlier[static_cast<std::size_t>(i)]) << i;
    }
    EXPECT_LT(r->rmsErrorPx, 1e-4);
  }
}

TEST(CameraResection, FindsNoPoseFromTooFewPointsAndRefusesBadInput)
{
  const Scene s = scene();
  const std::vector<Eigen::Vector3d> five(s.points.begin() + 1, s.points.begin() + 6);
  const std::vector<Eigen::Vector2d> fivePixels(s.pixels.begin() + 1, s.pixels.begin() + 6);
  EXPECT_FALSE(resectCamera(five, fivePixels, PinholeCamera::simulatedEndoscope(), {}));
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] { resectCamera(five, s.pixels, PinholeCamera::simulatedEndoscope(), {}); }),
    "camera resection: 5 points but 120 pixels");
  CameraResectionOptions fromGuess;
  fromGuess.solver = ResectionSolver::IterativeFromGuess;
  EXPECT_EQ(
    fixtures::errorMessageOf(
      [&] { resectCamera(s.points, s.pixels, PinholeCamera::simulatedEndoscope(), fromGuess); }),
    "camera resection: the iterative solver needs a starting pose");
  CameraResectionOptions threshold;
  threshold.thresholdPx = 0.0;
  EXPECT_EQ(
    fixtures::errorMessageOf(
      [&] { resectCamera(s.points, s.pixels, PinholeCamera::simulatedEndoscope(), threshold); }),
    "camera resection: the inlier threshold must be positive, not 0 px");
}
