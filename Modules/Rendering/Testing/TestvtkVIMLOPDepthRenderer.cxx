#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Rendering/vtkVIMLOPDepthRenderer.h>

#include <gtest/gtest.h>

#include <vtkNew.h>
#include <vtkPlaneSource.h>
#include <vtkSphereSource.h>

#include <cmath>

using namespace vimlop;

namespace
{

PinholeCamera makeCamera()
{
  PinholeCamera k;
  k.fx = 300.0;
  k.fy = 280.0; // non-square pixels
  k.cx = 150.3; // principal point off centre
  k.cy = 100.7;
  k.widthPx = 320;
  k.heightPx = 240;
  return k;
}

CameraPose makePose()
{
  CameraPose pose;
  pose.rotation = rotationFromVector(Eigen::Vector3d(0.3, -0.5, 0.2));
  pose.centre = Eigen::Vector3d(12.0, -7.0, 30.0);
  return pose;
}

} // namespace

TEST(vtkVIMLOPDepthRenderer, PlaneFacingTheCameraHasConstantDepth)
{
  const PinholeCamera k = makeCamera();
  const CameraPose pose = makePose();
  // A large square 100 mm in front of the camera, perpendicular to its axis.
  Eigen::Vector3d origin = pose.cameraToWorld({ -500, -500, 100 });
  Eigen::Vector3d point1 = pose.cameraToWorld({ 500, -500, 100 });
  Eigen::Vector3d point2 = pose.cameraToWorld({ -500, 500, 100 });
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(origin.data());
  plane->SetPoint1(point1.data());
  plane->SetPoint2(point2.data());
  plane->Update();

  vtkNew<vtkVIMLOPDepthRenderer> renderer;
  renderer->SetSurface(plane->GetOutput());
  const DepthMap depth = renderer->RenderDepth(k, pose);
  ASSERT_EQ(depth.widthPx, 320);
  ASSERT_EQ(depth.heightPx, 240);
  for (int v = 0; v < depth.heightPx; v += 7)
  {
    for (int u = 0; u < depth.widthPx; u += 7)
    {
      ASSERT_NEAR(depth.at(u, v), 100.0, 0.01) << u << "," << v;
    }
  }
}

TEST(vtkVIMLOPDepthRenderer, SphereDepthMatchesRayCasting)
{
  const PinholeCamera k = makeCamera();
  const CameraPose pose = makePose();
  // Off-axis, upper left of the image in camera coordinates (x < 0, y < 0).
  const Eigen::Vector3d centreCamera(-9.0, -6.0, 70.0);
  const double radius = 8.0;
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(pose.cameraToWorld(centreCamera).data());
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(256);
  sphere->SetPhiResolution(256);
  sphere->Update();

  vtkNew<vtkVIMLOPDepthRenderer> renderer;
  renderer->SetSurface(sphere->GetOutput());
  const DepthMap depth = renderer->RenderDepth(k, pose);

  int hits = 0;
  int misses = 0;
  double worst = 0.0;
  for (int v = 0; v < k.heightPx; ++v)
  {
    for (int u = 0; u < k.widthPx; ++u)
    {
      // Ray with unit z through the pixel centre: x(t) = t d, depth = t.
      const Eigen::Vector3d d((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
      const double bq = d.dot(centreCamera);
      const double disc =
        bq * bq - d.squaredNorm() * (centreCamera.squaredNorm() - radius * radius);
      const double margin = 0.05 * d.squaredNorm() * radius * radius; // keep off the limb
      if (disc > margin)
      {
        const double t = (bq - std::sqrt(disc)) / d.squaredNorm();
        worst = std::max(worst, std::abs(depth.at(u, v) - t));
        ++hits;
      }
      else if (disc < -margin)
      {
        ASSERT_TRUE(std::isinf(depth.at(u, v))) << u << "," << v;
        ++misses;
      }
    }
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 10000);
  EXPECT_LT(worst, 0.05);
}

TEST(vtkVIMLOPDepthRenderer, RefusesToRenderWithoutASurface)
{
  vtkNew<vtkVIMLOPDepthRenderer> renderer;
  try
  {
    renderer->RenderDepth(makeCamera(), makePose());
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "depth rendering: no surface was set");
  }
}
