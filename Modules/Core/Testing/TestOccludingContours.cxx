#include "TestMeshes.h"
#include <vimlop/Core/OccludingContours.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>

using namespace vimlop;

namespace
{

PinholeCamera makeCamera()
{
  PinholeCamera k;
  k.fx = k.fy = 400.0;
  k.cx = 319.5;
  k.cy = 239.5;
  k.widthPx = 640;
  k.heightPx = 480;
  return k;
}

} // namespace

TEST(OccludingContours, SilhouetteOfABlobIsItsOutline)
{
  // A solid sphere in the air (normals outward, into the air) seen from outside.
  const double r = 5.0;
  const Eigen::Vector3d centre(1.0, -2.0, 40.0);
  const TriangleMesh blob = fixtures::makeSphere(r, 4, centre, /*outward=*/true);
  const PinholeCamera k = makeCamera();
  const CameraPose camera; // at the origin, looking along +z
  const std::vector<ModelContourPoint> contour = extractOccludingContours(blob, k, camera);
  ASSERT_GT(contour.size(), 100u);

  const Eigen::Vector2d centrePixel = k.project(centre);
  // Apparent radius of a sphere: f r / sqrt(D² - r²) along the axis (small off-axis effect).
  const double D = centre.norm();
  const double radiusPx = k.fx * r / std::sqrt(D * D - r * r);
  double circumference = 2.0 * M_PI * radiusPx;
  for (const ModelContourPoint& p : contour)
  {
    // On the outline: the viewing ray is tangent to the sphere there.
    const Eigen::Vector3d ray = (p.point - camera.centre).normalized();
    EXPECT_LT(std::abs(ray.dot((p.point - centre).normalized())), 0.06);
    EXPECT_NEAR((p.pixel - centrePixel).norm(), radiusPx, 0.05 * radiusPx);
    EXPECT_LT((k.project(camera.worldToCamera(p.point)) - p.pixel).norm(), 1e-9);
    // The normal points away from the occluding blob, towards the background.
    EXPECT_GT(p.pixelNormal.dot((p.pixel - centrePixel).normalized()), 0.9);
    EXPECT_NEAR(p.pixelNormal.norm(), 1.0, 1e-12);
  }
  // Sampled about once per pixel along the outline (zig-zag edges add some).
  EXPECT_GT(static_cast<double>(contour.size()), 0.9 * circumference);
  EXPECT_LT(static_cast<double>(contour.size()), 2.0 * circumference);
}

TEST(OccludingContours, ConvexCavityHasNoContours)
{
  // From inside a convex cavity every face faces the camera.
  const TriangleMesh box = fixtures::makeBox({ -10, -10, -10 }, { 10, 10, 30 });
  EXPECT_TRUE(extractOccludingContours(box, makeCamera(), CameraPose()).empty());
}

TEST(OccludingContours, SamplesStayInTheImageAndInFront)
{
  const TriangleMesh cavity = fixtures::makeCavityWithBlobs();
  const PinholeCamera k = makeCamera();
  // Looking at the blob centred at (8, 0, 3) from the other side of the cavity.
  const CameraPose camera = CameraPose::lookAt({ -10, -3, 0 }, { 8, 0, 3 }, { 0, 0, 1 });
  OccludingContourOptions options;
  options.imageMarginPx = 2.0;
  options.sampleSpacingPx = 3.0;
  const auto coarse = extractOccludingContours(cavity, k, camera, options);
  ASSERT_FALSE(coarse.empty());
  for (const ModelContourPoint& p : coarse)
  {
    EXPECT_TRUE(k.isInImage(p.pixel, 2.0));
    EXPECT_GT(camera.worldToCamera(p.point).z(), 0.1);
  }
  options.sampleSpacingPx = 1.0;
  const auto fine = extractOccludingContours(cavity, k, camera, options);
  EXPECT_GT(fine.size(), 2 * coarse.size());
}

TEST(OccludingContours, InterpolatedNormalsTraceTheSmoothOutline)
{
  // The same blob: the smooth generator's samples lie inside faces where the
  // interpolated normal is (up to its normalisation) perpendicular to the
  // viewing ray, far more so than the mean face normal on a mesh edge.
  const double r = 5.0;
  const Eigen::Vector3d centre(1.0, -2.0, 40.0);
  const TriangleMesh blob = fixtures::makeSphere(r, 4, centre, /*outward=*/true);
  const PinholeCamera k = makeCamera();
  OccludingContourOptions options;
  options.generator = ContourGenerator::InterpolatedNormals;
  const auto smooth = extractOccludingContours(blob, k, CameraPose(), options);
  const auto edges = extractOccludingContours(blob, k, CameraPose());
  ASSERT_GT(smooth.size(), 100u);
  const Eigen::Vector2d centrePixel = k.project(centre);
  auto meanTangency = [](const std::vector<ModelContourPoint>& samples)
  {
    double sum = 0.0;
    for (const ModelContourPoint& p : samples)
    {
      sum += std::abs(p.normal.dot(p.point.normalized()));
    }
    return sum / samples.size();
  };
  for (const ModelContourPoint& p : smooth)
  {
    ASSERT_LT(std::abs(p.normal.dot(p.point.normalized())), 1e-3);
    ASSERT_GT(p.pixelNormal.dot((p.pixel - centrePixel).normalized()), 0.95);
  }
  EXPECT_LT(meanTangency(smooth), 0.1 * meanTangency(edges));
}
