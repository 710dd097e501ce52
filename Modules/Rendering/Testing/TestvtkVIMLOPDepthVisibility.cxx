#include "CraniumAirway.h"
#include "CraniumPoses.h"
#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/MeshTreeVisibility.h>
#include <vimlop/Core/OccludingContours.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Raycast/EmbreeVisibility.h>
#include <vimlop/Rendering/vtkVIMLOPDepthVisibility.h>

#include <gtest/gtest.h>

#include <vtkNew.h>

#include <iostream>
#include <random>

using namespace vimlop;

namespace
{

struct Agreement
{
  size_t total = 0;
  size_t agree = 0;
  size_t hidden = 0; ///< by the reference
};

Agreement compare(const TriangleMesh& mesh, const ContourVisibility& reference,
  const ContourVisibility& tested, const std::vector<CameraPose>& poses)
{
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  Agreement a;
  for (const CameraPose& pose : poses)
  {
    std::vector<Eigen::Vector3d> points;
    for (const ModelContourPoint& s : extractOccludingContours(mesh, k, pose))
    {
      points.push_back(s.point);
    }
    std::vector<char> expected, actual;
    reference.classify(k, pose, points, expected);
    tested.classify(k, pose, points, actual);
    for (size_t i = 0; i < points.size(); ++i)
    {
      a.agree += expected[i] == actual[i];
      a.hidden += expected[i] == 0;
    }
    a.total += points.size();
  }
  return a;
}

} // namespace

TEST(vtkVIMLOPDepthVisibility, AgreesWithTheExactReferenceOnAFixture)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  vtkNew<vtkVIMLOPDepthVisibility> depth;
  depth->SetMesh(mesh);
  const MeshTreeVisibility reference(std::make_shared<MeshTree>(mesh));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-8.0, 8.0);
  std::vector<CameraPose> poses;
  for (int view = 0; view < 12; ++view)
  {
    poses.push_back(CameraPose::lookAt({ u(rng), u(rng), u(rng) }, { 8, 0, 3 }, { 0, 0, 1 }));
  }
  const Agreement a = compare(mesh, reference, *depth, poses);
  ASSERT_GT(a.total, 1000u);
  EXPECT_GT(a.hidden, a.total / 50); // the blobs hide part of the cavity's contours
  EXPECT_GE(static_cast<double>(a.agree), 0.98 * a.total);
}

TEST(vtkVIMLOPDepthVisibility, AgreesWithEmbreeOnTheCraniumAirway)
{
  const TriangleMesh mesh = fixtures::craniumAirwayMesh();
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  const std::vector<CameraPose> poses = fixtures::posesInside(model, 8);
  ASSERT_GE(poses.size(), 80u);
  vtkNew<vtkVIMLOPDepthVisibility> depth;
  depth->SetMesh(mesh);
  const Agreement a = compare(mesh, model.visibility(), *depth, poses);
  const double percent = 100.0 * a.agree / a.total;
  std::cout << "z-buffer and Embree visibility agree on " << percent << " % of " << a.total
            << " contour samples (" << a.hidden << " hidden by Embree) over " << poses.size()
            << " poses\n";
  ASSERT_GT(a.total, 10000u);
  EXPECT_GT(a.hidden, a.total / 20);
  EXPECT_GE(percent, 98.0);
}

TEST(vtkVIMLOPDepthVisibility, ReportsMisuse)
{
  vtkNew<vtkVIMLOPDepthVisibility> depth;
  EXPECT_FALSE(depth->isThreadSafe());
  std::vector<char> visible;
  const std::vector<Eigen::Vector3d> points = { { 0, 0, 10 } };
  try
  {
    depth->classify(PinholeCamera::simulatedEndoscope(), CameraPose(), points, visible);
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "depth visibility: no mesh was set");
  }
  try
  {
    depth->SetMesh(TriangleMesh());
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "depth visibility: the mesh has no faces");
  }
  // No points: nothing to render, nothing to classify.
  depth->classify(PinholeCamera::simulatedEndoscope(), CameraPose(), {}, visible);
  EXPECT_TRUE(visible.empty());
}
