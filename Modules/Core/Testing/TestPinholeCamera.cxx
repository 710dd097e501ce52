#include "ErrorMessage.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/PinholeCamera.h>

#include <gtest/gtest.h>

using namespace vimlop;

namespace
{

PinholeCamera makeCamera()
{
  PinholeCamera camera;
  camera.fx = 500.0;
  camera.fy = 480.0;
  camera.cx = 319.5;
  camera.cy = 240.0;
  camera.widthPx = 640;
  camera.heightPx = 480;
  return camera;
}

} // namespace

TEST(PinholeCamera, ProjectsWithTheOpenCVConvention)
{
  const PinholeCamera camera = makeCamera();
  // On the optical axis: the principal point.
  EXPECT_LT((camera.project({ 0, 0, 10 }) - Eigen::Vector2d(319.5, 240.0)).norm(), 1e-12);
  // x right, y down.
  const Eigen::Vector2d p = camera.project({ 1.0, 2.0, 10.0 });
  EXPECT_NEAR(p.x(), 319.5 + 50.0, 1e-12);
  EXPECT_NEAR(p.y(), 240.0 + 96.0, 1e-12);
}

TEST(PinholeCamera, BackProjectInvertsProject)
{
  const PinholeCamera camera = makeCamera();
  const Eigen::Vector3d x(-3.0, 1.5, 25.0);
  const Eigen::Vector2d pixel = camera.project(x);
  EXPECT_LT((camera.backProject(pixel, x.z()) - x).norm(), 1e-12);
  EXPECT_LT((camera.rayDirection(pixel) - x.normalized()).norm(), 1e-12);
}

TEST(PinholeCamera, InImageUsesPixelCentres)
{
  const PinholeCamera camera = makeCamera();
  EXPECT_TRUE(camera.isInImage({ -0.5, -0.5 }));
  EXPECT_TRUE(camera.isInImage({ 639.5, 479.5 }));
  EXPECT_FALSE(camera.isInImage({ 639.6, 10.0 }));
  EXPECT_FALSE(camera.isInImage({ 10.0, -0.6 }));
  EXPECT_FALSE(camera.isInImage({ 2.0, 100.0 }, 3.0));
  EXPECT_TRUE(camera.isInImage({ 2.5, 100.0 }, 3.0));
}

TEST(PinholeCamera, MatrixRoundTrip)
{
  const PinholeCamera camera = makeCamera();
  const PinholeCamera back = PinholeCamera::fromMatrix(camera.matrix(), 640, 480);
  EXPECT_EQ(back.fx, camera.fx);
  EXPECT_EQ(back.cy, camera.cy);
  Eigen::Matrix3d skewed = camera.matrix();
  skewed(0, 1) = 1.0;
  EXPECT_THROW(PinholeCamera::fromMatrix(skewed, 640, 480), Error);
}

TEST(PinholeCamera, ValidateNamesTheProblem)
{
  PinholeCamera camera = makeCamera();
  EXPECT_NO_THROW(camera.validate());
  camera.fy = 0.0;
  try
  {
    camera.validate();
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "focal lengths must be positive (fx=500, fy=0)");
  }
  camera = makeCamera();
  camera.widthPx = 0;
  EXPECT_THROW(camera.validate(), Error);
  camera = makeCamera();
  camera.cx = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(camera.validate(), Error);
  camera = makeCamera();
  camera.cx = 5000.0;
  EXPECT_THROW(camera.validate(), Error);
}

TEST(PinholeCamera, IntrinsicsInOtherUnitsThanPixelsAreRefusedWithTheUnitsNamed)
{
  // The simulated endoscope's 200 px focal length as mm of a 2.8 mm lens,
  // and as the focal length of an image ten times larger in micrometres.
  PinholeCamera k = PinholeCamera::simulatedEndoscope();
  k.fx = k.fy = 2.8;
  EXPECT_EQ(vimlop::fixtures::errorMessageOf([&] { k.validate(); }),
    "focal lengths (fx=2.8, fy=2.8) are far too small for a 320x240 image (a field of view over "
    "168 deg): intrinsics are in pixels, not mm or normalised");
  k.fx = k.fy = 7000.0;
  EXPECT_EQ(vimlop::fixtures::errorMessageOf([&] { k.validate(); }),
    "focal lengths (fx=7000, fy=7000) are far too large for a 320x240 image (a field of view "
    "under 3 deg): are they for a larger image, or in other units than pixels?");
  k.fx = k.fy = 0.3 * 320.0; // a wide-angle scope: 118 deg across
  EXPECT_NO_THROW(k.validate());
}

TEST(PinholeCamera, TheSimulatedEndoscopeIsValidWithItsPrincipalPointAtTheCentre)
{
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  EXPECT_NO_THROW(k.validate());
  EXPECT_EQ(k.widthPx, 320);
  EXPECT_EQ(k.heightPx, 240);
  EXPECT_DOUBLE_EQ(k.cx, 0.5 * (k.widthPx - 1));
  EXPECT_DOUBLE_EQ(k.cy, 0.5 * (k.heightPx - 1));
  // 77 degrees across: 2 atan(160 / 200).
  EXPECT_NEAR(2.0 * std::atan(0.5 * k.widthPx / k.fx) * 180.0 / M_PI, 77.3, 0.1);
}

TEST(PinholeCamera, AFisheyeLensNeedsExactlyFourCoefficientsAndRemovingTheLensMakesAPinhole)
{
  PinholeCamera k = makeCamera();
  EXPECT_EQ(k.lensModel, LensModel::RadialTangential);
  k.lensModel = LensModel::Fisheye;
  k.distortion = Eigen::Vector4d(0.03, -0.01, 0.002, -0.0005);
  EXPECT_NO_THROW(k.validate());
  k.distortion = Eigen::Vector3d(0.03, -0.01, 0.002);
  EXPECT_EQ(fixtures::errorMessageOf([&] { k.validate(); }),
    "the fisheye lens model needs exactly 4 distortion coefficients (k1, k2, k3, k4), not 3");
  k.removeDistortion();
  EXPECT_EQ(k.distortion.size(), 0);
  EXPECT_EQ(k.lensModel, LensModel::RadialTangential);
  EXPECT_NO_THROW(k.validate());
}

TEST(PinholeCamera, ARadialTangentialLensTakesOnlyTheCoefficientCountsOpenCVKnows)
{
  PinholeCamera k = makeCamera();
  for (int n : { 0, 4, 5, 8, 12, 14 })
  {
    k.distortion = Eigen::VectorXd::Constant(n, 0.01);
    EXPECT_NO_THROW(k.validate()) << n;
  }
  k.distortion = Eigen::VectorXd::Constant(7, 0.01);
  EXPECT_EQ(fixtures::errorMessageOf([&] { k.validate(); }),
    "the radial-tangential lens model needs 4, 5, 8, 12 or 14 distortion coefficients (OpenCV's "
    "k1, k2, p1, p2[, k3[, k4, k5, k6[, s1, s2, s3, s4[, tx, ty]]]]), not 7");
}
