#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Video/BundleAdjustment.h>

#include <gtest/gtest.h>

#include <random>

using namespace vimlop;

namespace
{

struct Scene
{
  std::vector<CameraPose> cameras;
  std::vector<Eigen::Vector3d> points;
  std::vector<PinholeCamera> intrinsics;
  std::vector<BundleAdjustment::Observation> observations;
};

PinholeCamera camera()
{
  PinholeCamera k;
  k.fx = k.fy = 200.0;
  k.cx = 159.5;
  k.cy = 119.5;
  k.widthPx = 320;
  k.heightPx = 240;
  return k;
}

/// Six cameras moving along x and z, looking down +z at points 8-20 units
/// away, observed with Gaussian noise of `noisePx`; camera 0 at the origin.
Scene makeScene(double noisePx, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noisePx);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Scene s;
  for (int c = 0; c < 6; ++c)
  {
    CameraPose pose;
    if (c > 0)
    {
      pose.rotation = rotationFromVector(Eigen::Vector3d(0.02 * c, -0.03 * c, 0.01 * c));
      pose.centre = Eigen::Vector3d(0.5 * c, 0.1 * c, 0.4 * c);
    }
    s.cameras.push_back(pose);
    s.intrinsics.push_back(camera());
  }
  for (int i = 0; i < 200; ++i)
  {
    const Eigen::Vector3d p(6.0 * u(rng), 4.0 * u(rng), 14.0 + 6.0 * u(rng));
    s.points.push_back(p);
    for (int c = 0; c < 6; ++c)
    {
      const Eigen::Vector3d x = s.cameras[c].worldToCamera(p);
      const Eigen::Vector2d pixel = camera().project(x) + Eigen::Vector2d(noise(rng), noise(rng));
      s.observations.push_back({ c, i, pixel });
    }
  }
  return s;
}

} // namespace

TEST(BundleAdjustment, RecoversCamerasAndPointsFromAPerturbedStart)
{
  const Scene truth = makeScene(0.5, 1);
  Scene start = truth;
  std::mt19937 rng(2);
  std::normal_distribution<double> n(0.0, 1.0);
  for (size_t c = 1; c < start.cameras.size(); ++c)
  {
    start.cameras[c].rotation = rotationFromVector(0.01 * Eigen::Vector3d(n(rng), n(rng), n(rng))) *
      start.cameras[c].rotation;
    start.cameras[c].centre += 0.05 * Eigen::Vector3d(n(rng), n(rng), n(rng));
  }
  for (Eigen::Vector3d& p : start.points)
  {
    p += 0.3 * Eigen::Vector3d(n(rng), n(rng), n(rng));
  }
  BundleAdjustmentOptions options;
  options.scaleCamera = 5;
  const double fixedComponentBefore = [&]
  {
    const Eigen::Vector3d t = -start.cameras[5].rotation.transpose() * start.cameras[5].centre;
    Eigen::Index axis = 0;
    t.cwiseAbs().maxCoeff(&axis);
    return t[axis];
  }();
  const BundleAdjustment::Summary summary = BundleAdjustment::adjust(
    start.cameras, start.points, start.intrinsics, start.observations, { 0 }, options);
  EXPECT_GT(summary.initialRmsPx, 5.0);
  // The residual is the image noise: 0.5 px per axis, 0.71 px in the image,
  // less what the 630 fitted parameters absorb of the 2400 residuals (0.61 px).
  EXPECT_GT(summary.finalRmsPx, 0.55);
  EXPECT_LT(summary.finalRmsPx, 0.67);
  // The fixed camera did not move; the scale camera kept its held component.
  EXPECT_EQ(start.cameras[0].centre, truth.cameras[0].centre);
  const Eigen::Vector3d t5 = -start.cameras[5].rotation.transpose() * start.cameras[5].centre;
  EXPECT_NEAR(t5.cwiseAbs().maxCoeff(), std::abs(fixedComponentBefore), 1e-12);
  // It converged: started from the truth instead, it ends at the same place.
  Scene fromTruth = truth;
  BundleAdjustment::adjust(fromTruth.cameras, fromTruth.points, fromTruth.intrinsics,
    fromTruth.observations, { 0 }, options);
  const double scale = fromTruth.cameras[5].centre.norm() / start.cameras[5].centre.norm();
  for (size_t c = 1; c < truth.cameras.size(); ++c)
  {
    EXPECT_LT((scale * start.cameras[c].centre - fromTruth.cameras[c].centre).norm(), 1e-4) << c;
    EXPECT_LT(rotationAngleBetween(start.cameras[c].rotation, fromTruth.cameras[c].rotation), 1e-5)
      << c;
    // And within the noise of the truth.
    EXPECT_LT((scale * start.cameras[c].centre - truth.cameras[c].centre).norm(), 0.05) << c;
    EXPECT_LT(
      rotationAngleBetween(start.cameras[c].rotation, truth.cameras[c].rotation) * 180.0 / M_PI,
      0.3)
      << c;
  }
}

TEST(BundleAdjustment, HuberWeightsKeepOutliersFromPullingPoints)
{
  const Scene truth = makeScene(0.3, 3);
  auto medianPointError = [&](const Scene& adjusted)
  {
    std::vector<double> errors;
    for (size_t i = 0; i < truth.points.size(); ++i)
    {
      errors.push_back((adjusted.points[i] - truth.points[i]).norm());
    }
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    return errors[errors.size() / 2];
  };
  Scene clean = truth;
  BundleAdjustment::adjust(
    clean.cameras, clean.points, clean.intrinsics, clean.observations, { 0, 1 });
  // One observation in twenty is a mismatch, up to 40 px off.
  Scene withOutliers = truth;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> offset(-40.0, 40.0);
  std::uniform_int_distribution<int> pick(0, 19);
  for (BundleAdjustment::Observation& o : withOutliers.observations)
  {
    if (pick(rng) == 0)
    {
      o.pixel += Eigen::Vector2d(offset(rng), offset(rng));
    }
  }
  Scene plain = withOutliers;
  Scene robust = withOutliers;
  BundleAdjustmentOptions leastSquares;
  leastSquares.huberPx = 1e9;
  BundleAdjustment::adjust(
    plain.cameras, plain.points, plain.intrinsics, plain.observations, { 0, 1 }, leastSquares);
  BundleAdjustment::adjust(
    robust.cameras, robust.points, robust.intrinsics, robust.observations, { 0, 1 });
  EXPECT_LT(medianPointError(robust), 2.0 * medianPointError(clean));
  EXPECT_LT(medianPointError(robust), 0.3 * medianPointError(plain));
}

TEST(BundleAdjustment, RejectsBadIndices)
{
  Scene s = makeScene(0.0, 4);
  std::vector<BundleAdjustment::Observation> bad = s.observations;
  bad.push_back({ 9, 0, Eigen::Vector2d::Zero() });
  EXPECT_THROW(BundleAdjustment::adjust(s.cameras, s.points, s.intrinsics, bad, { 0 }), Error);
  EXPECT_THROW(
    BundleAdjustment::adjust(s.cameras, s.points, s.intrinsics, s.observations, { 7 }), Error);
  std::vector<PinholeCamera> tooFew(2, camera());
  EXPECT_THROW(BundleAdjustment::adjust(s.cameras, s.points, tooFew, s.observations, { 0 }), Error);
}
