#include "CraniumAirway.h"
#include "CraniumPoses.h"
#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/OccludingContours.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Rendering/vtkVIMLOPSilhouetteRenderer.h>

#include <gtest/gtest.h>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <cmath>
#include <iostream>

using namespace vimlop;

namespace
{

bool isOn(vtkImageData* mask, int u, int v)
{
  int dims[3];
  mask->GetDimensions(dims);
  if (u < 0 || v < 0 || u >= dims[0] || v >= dims[1])
  {
    return false;
  }
  // Pixel (u, v), v down, is at row heightPx - 1 - v of the VTK image.
  return *static_cast<unsigned char*>(mask->GetScalarPointer(u, dims[1] - 1 - v, 0)) > 0;
}

/// Whether a drawn pixel centre lies within `radiusPx` of `pixel`.
bool drawnNear(vtkImageData* mask, const Eigen::Vector2d& pixel, double radiusPx)
{
  const int r = static_cast<int>(std::ceil(radiusPx)) + 1;
  const int u0 = static_cast<int>(std::lround(pixel.x()));
  const int v0 = static_cast<int>(std::lround(pixel.y()));
  for (int v = v0 - r; v <= v0 + r; ++v)
  {
    for (int u = u0 - r; u <= u0 + r; ++u)
    {
      if ((Eigen::Vector2d(u, v) - pixel).norm() <= radiusPx && isOn(mask, u, v))
      {
        return true;
      }
    }
  }
  return false;
}

struct PixelAgreement
{
  size_t samples = 0;         ///< visible Core samples
  size_t samplesDrawn = 0;    ///< of which have a drawn pixel within 1 px
  size_t drawn = 0;           ///< drawn pixels
  size_t drawnNearSample = 0; ///< of which lie within 1.5 px of a visible Core sample
};

PixelAgreement compare(const RegistrationModel& model, vtkVIMLOPSilhouetteRenderer* renderer,
  const std::vector<CameraPose>& poses)
{
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  PixelAgreement a;
  for (const CameraPose& pose : poses)
  {
    const std::vector<ModelContourPoint> samples = extractOccludingContours(model.mesh(), k, pose);
    std::vector<Eigen::Vector3d> points;
    for (const ModelContourPoint& s : samples)
    {
      points.push_back(s.point);
    }
    std::vector<char> visible;
    model.visibility().classify(k, pose, points, visible);
    vtkSmartPointer<vtkImageData> mask = renderer->RenderContours(k, pose);
    std::vector<char> nearSample(static_cast<size_t>(k.widthPx) * k.heightPx, 0);
    for (size_t i = 0; i < samples.size(); ++i)
    {
      if (!visible[i])
      {
        continue;
      }
      ++a.samples;
      a.samplesDrawn += drawnNear(mask, samples[i].pixel, 1.0);
      const int u0 = static_cast<int>(std::lround(samples[i].pixel.x()));
      const int v0 = static_cast<int>(std::lround(samples[i].pixel.y()));
      for (int v = std::max(0, v0 - 2); v <= std::min(k.heightPx - 1, v0 + 2); ++v)
      {
        for (int u = std::max(0, u0 - 2); u <= std::min(k.widthPx - 1, u0 + 2); ++u)
        {
          if ((Eigen::Vector2d(u, v) - samples[i].pixel).norm() <= 1.5)
          {
            nearSample[static_cast<size_t>(v) * k.widthPx + u] = 1;
          }
        }
      }
    }
    for (int v = 0; v < k.heightPx; ++v)
    {
      for (int u = 0; u < k.widthPx; ++u)
      {
        if (isOn(mask, u, v))
        {
          ++a.drawn;
          a.drawnNearSample += nearSample[static_cast<size_t>(v) * k.widthPx + u];
        }
      }
    }
  }
  return a;
}

} // namespace

TEST(vtkVIMLOPSilhouetteRenderer, DrawsTheOutlineOfABlob)
{
  // A solid sphere seen from outside: its outline is a circle of known radius.
  const double r = 5.0;
  const Eigen::Vector3d centre(1.0, -2.0, 40.0);
  const TriangleMesh blob = fixtures::makeSphere(r, 4, centre, /*outward=*/true);
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  vtkNew<vtkVIMLOPSilhouetteRenderer> renderer;
  renderer->SetMesh(blob);
  vtkSmartPointer<vtkImageData> mask = renderer->RenderContours(k, CameraPose());
  int dims[3];
  mask->GetDimensions(dims);
  ASSERT_EQ(dims[0], k.widthPx);
  ASSERT_EQ(dims[1], k.heightPx);
  const Eigen::Vector2d c = k.project(centre);
  const double radiusPx = k.fx * r / std::sqrt(centre.squaredNorm() - r * r);
  int on = 0;
  for (int v = 0; v < k.heightPx; ++v)
  {
    for (int u = 0; u < k.widthPx; ++u)
    {
      if (isOn(mask, u, v))
      {
        ++on;
        EXPECT_NEAR((Eigen::Vector2d(u, v) - c).norm(), radiusPx, 1.5) << u << "," << v;
      }
    }
  }
  // An 8-connected digital circle has about 4 sqrt(2) r pixels.
  EXPECT_GT(on, 0.8 * 4.0 * std::sqrt(2.0) * radiusPx);
  // Every one of Core's contour samples (all visible on a convex blob) is
  // drawn nearby. VTK picks contour edges by the faces' orientation seen
  // from the edge's midpoint, Core by the faces' centroids: where the two
  // rules pick neighbouring edges the lines are up to an edge (1.5 px here) apart.
  const std::vector<ModelContourPoint> samples = extractOccludingContours(blob, k, CameraPose());
  ASSERT_GT(samples.size(), 100u);
  size_t within1 = 0;
  size_t within2 = 0;
  for (const ModelContourPoint& s : samples)
  {
    within1 += drawnNear(mask, s.pixel, 1.0);
    within2 += drawnNear(mask, s.pixel, 2.0);
  }
  EXPECT_GE(within1, samples.size() * 90 / 100);
  EXPECT_EQ(within2, samples.size());
  EXPECT_GT(renderer->GetContourEdges()->GetNumberOfLines(), 20);
}

TEST(vtkVIMLOPSilhouetteRenderer, MatchesCoreContoursOnTheCraniumAirway)
{
  const TriangleMesh mesh = fixtures::craniumAirwayMesh();
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  const std::vector<CameraPose> poses = fixtures::posesInside(model, 6);
  vtkNew<vtkVIMLOPSilhouetteRenderer> renderer;
  renderer->SetMesh(mesh);
  const PixelAgreement a = compare(model, renderer, poses);
  const double samplesPercent = 100.0 * a.samplesDrawn / a.samples;
  const double drawnPercent = 100.0 * a.drawnNearSample / a.drawn;
  std::cout << "VTK silhouettes: " << samplesPercent << " % of " << a.samples
            << " visible Core contour samples have a drawn pixel within 1 px; " << drawnPercent
            << " % of " << a.drawn << " drawn pixels lie within 1.5 px of a sample ("
            << poses.size() << " poses)\n";
  ASSERT_GT(a.samples, 5000u);
  EXPECT_GE(samplesPercent, 95.0);
  EXPECT_GE(drawnPercent, 90.0);
}

TEST(vtkVIMLOPSilhouetteRenderer, ReportsMisuse)
{
  vtkNew<vtkVIMLOPSilhouetteRenderer> renderer;
  try
  {
    renderer->RenderContours(PinholeCamera::simulatedEndoscope(), CameraPose());
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "silhouette rendering: no mesh was set");
  }
}
