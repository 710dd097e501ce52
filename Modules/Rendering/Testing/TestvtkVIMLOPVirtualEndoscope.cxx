#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Rendering/VTKCameraAdapter.h>
#include <vimlop/Rendering/vtkVIMLOPVirtualEndoscope.h>

#include <gtest/gtest.h>

#include <vtkNew.h>

#include <cmath>

using namespace vimlop;

namespace
{

PinholeCamera makeCamera()
{
  PinholeCamera k;
  k.fx = k.fy = 100.0;
  k.cx = 79.5;
  k.cy = 59.5;
  k.widthPx = 160;
  k.heightPx = 120;
  return k;
}

CameraPose makePose()
{
  CameraPose pose;
  pose.rotation = rotationFromVector(Eigen::Vector3d(0.2, -0.3, 0.1));
  pose.centre = Eigen::Vector3d(5.0, -3.0, 12.0);
  return pose;
}

/// A square [-half, half]^2 + offset (camera x, y) at camera depth `depth`, n x n quads, facing the
/// camera (normals towards it: into the air the camera is in), in the world
/// frame of `pose`.
TriangleMesh facingSquare(const CameraPose& pose, double depth, double half, int n = 40,
  const Eigen::Vector2d& offset = Eigen::Vector2d::Zero())
{
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      v.push_back(pose.cameraToWorld(
        { offset.x() - half + 2.0 * half * i / n, offset.y() - half + 2.0 * half * j / n, depth }));
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const int a = j * (n + 1) + i;
      // (a, c, b) with c the next row: the normal points to -z, the camera.
      f.emplace_back(a, a + n + 1, a + 1);
      f.emplace_back(a + 1, a + n + 1, a + n + 2);
    }
  }
  return TriangleMesh(std::move(v), std::move(f));
}

TriangleMesh merge(const TriangleMesh& a, const TriangleMesh& b)
{
  std::vector<Eigen::Vector3d> v = a.vertices();
  std::vector<Eigen::Vector3i> f = a.faces();
  const int offset = a.numberOfVertices();
  v.insert(v.end(), b.vertices().begin(), b.vertices().end());
  for (const Eigen::Vector3i& t : b.faces())
  {
    f.push_back(t + Eigen::Vector3i::Constant(offset));
  }
  return TriangleMesh(std::move(v), std::move(f));
}

/// A texture without any pattern: the base colour everywhere.
MucosaTexture plainTexture()
{
  MucosaTextureOptions o;
  o.patchAmplitude = 0.0;
  o.mottleAmplitude.setZero();
  o.vesselTransmission.setOnes();
  return MucosaTexture(o);
}

/// What the endoscope should show for an albedo seen head-on at distance r.
double expectedValue(vtkVIMLOPVirtualEndoscope* e, double albedo, double r, double cosine)
{
  const double r0 = e->GetReferenceDistanceMm();
  const double d = e->GetDiffuseFraction();
  const double radiance = albedo * ((1.0 - d) + d * cosine) * r0 * r0 / (r * r) +
    e->GetSpecularStrength() * std::pow(cosine, e->GetSpecularPower()) * r0 * r0 / (r * r);
  const double x = radiance * e->GetExposure();
  return 255.0 * std::pow(x / (1.0 + x), 1.0 / 2.2);
}

double mean(const EndoscopeImage& image, int channel, int u0, int v0, int u1, int v1)
{
  double sum = 0.0;
  for (int v = v0; v < v1; ++v)
  {
    for (int u = u0; u < u1; ++u)
    {
      sum += image.channel(u, v, channel);
    }
  }
  return sum / ((u1 - u0) * (v1 - v0));
}

} // namespace

TEST(vtkVIMLOPVirtualEndoscope, ShowsTheLightAtTheCameraAndTheTrueDepth)
{
  const PinholeCamera k = makeCamera();
  const CameraPose pose = makePose();
  vtkNew<vtkVIMLOPVirtualEndoscope> endoscope;
  endoscope->SetNoiseSigma(0.0);
  endoscope->SetBlurSigmaPx(0.0);
  endoscope->SetMesh(facingSquare(pose, 8.0, 40.0), plainTexture());
  EXPECT_EQ(endoscope->GetNumberOfRenderedTriangles(), 16 * 2 * 40 * 40);
  const EndoscopeImage image = endoscope->Render(k, pose);
  ASSERT_EQ(image.widthPx, 160);
  ASSERT_EQ(image.heightPx, 120);
  ASSERT_EQ(image.rgb.size(), 160u * 120u * 3u);
  for (int v = 0; v < 120; v += 9)
  {
    for (int u = 0; u < 160; u += 9)
    {
      ASSERT_NEAR(image.depth.at(u, v), 8.0, 0.01) << u << "," << v;
    }
  }
  // At the principal point the surface faces the light 8 mm away.
  const Eigen::Vector3d albedo = plainTexture().options().baseColour;
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(mean(image, c, 78, 58, 82, 62), expectedValue(endoscope, albedo[c], 8.0, 1.0), 2.0)
      << "channel " << c;
  }
  // Off axis the light is farther and more oblique: darker towards the corners.
  EXPECT_LT(mean(image, 0, 0, 0, 10, 10), mean(image, 0, 75, 55, 85, 65) - 10.0);
}

TEST(vtkVIMLOPVirtualEndoscope, NearerTissueIsBrighterAcrossAnOccludingContour)
{
  // DESIGN §4: the light at the endoscope makes the occluding (near) side of
  // a contour brighter, which is why video contour normals are the negative
  // intensity gradient.
  const PinholeCamera k = makeCamera();
  const CameraPose pose = makePose();
  vtkNew<vtkVIMLOPVirtualEndoscope> endoscope;
  endoscope->SetNoiseSigma(0.0);
  endoscope->SetBlurSigmaPx(0.0);
  // A 4 mm square 10 mm away, in the upper half of the view (camera y < 0 is
  // up): u from 59.5 to 99.5 px, v from 9.5 to 49.5 px; behind it a wall at 16 mm.
  endoscope->SetMesh(merge(facingSquare(pose, 10.0, 2.0, 10, Eigen::Vector2d(0.0, -3.0)),
                       facingSquare(pose, 16.0, 60.0)),
    plainTexture());
  const EndoscopeImage image = endoscope->Render(k, pose);
  // Picture and depth rows run top-down, as in OpenCV.
  EXPECT_NEAR(image.depth.at(79, 29), 10.0, 0.01);
  EXPECT_NEAR(image.depth.at(79, 90), 16.0, 0.01);
  EXPECT_NEAR(image.depth.at(20, 29), 16.0, 0.01);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_GT(mean(image, c, 62, 20, 66, 40), mean(image, c, 52, 20, 56, 40) + 20.0);
    EXPECT_GT(mean(image, c, 70, 20, 90, 40), mean(image, c, 70, 80, 90, 100) + 20.0);
  }
  // The step sits on the square's projected edge (u = 59.5): anti-aliased
  // pixels only at u = 59 and 60.
  const double nearValue = mean(image, 0, 62, 20, 66, 40);
  const double farValue = mean(image, 0, 52, 20, 56, 40);
  EXPECT_NEAR(mean(image, 0, 61, 20, 62, 40), nearValue, 3.0);
  EXPECT_NEAR(mean(image, 0, 58, 20, 59, 40), farValue, 3.0);
}

TEST(vtkVIMLOPVirtualEndoscope, NoiseIsReproducible)
{
  const PinholeCamera k = makeCamera();
  const CameraPose pose = makePose();
  vtkNew<vtkVIMLOPVirtualEndoscope> endoscope;
  endoscope->SetSubdivisionLevels(1);
  endoscope->SetMesh(facingSquare(pose, 8.0, 40.0, 20));
  const EndoscopeImage a = endoscope->Render(k, pose, 3);
  const EndoscopeImage b = endoscope->Render(k, pose, 3);
  const EndoscopeImage c = endoscope->Render(k, pose, 4);
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_NE(a.rgb, c.rgb);
}

TEST(vtkVIMLOPVirtualEndoscope, RefusesToRenderWithoutAMesh)
{
  vtkNew<vtkVIMLOPVirtualEndoscope> endoscope;
  EXPECT_THROW(endoscope->Render(makeCamera(), makePose()), Error);
  EXPECT_THROW(endoscope->SetMesh(TriangleMesh()), Error);
  endoscope->SetMesh(facingSquare(makePose(), 8.0, 40.0, 4));
  PinholeCamera bad = makeCamera();
  bad.fx = -1.0;
  EXPECT_THROW(endoscope->Render(bad, makePose()), Error);
}
