#include "TestMeshes.h"
#include <vimlop/Core/MeshTreeVisibility.h>
#include <vimlop/Core/RegistrationResult.h>
#include <vimlop/Core/VisibleModelContours.h>

#include <gtest/gtest.h>

using namespace vimlop;

using fixtures::twoBlobs;
using fixtures::twoBlobsCamera;

TEST(VisibleModelContours, KeepsExactlyTheSamplesTheVisibilityBackendSees)
{
  const RegistrationModel model(twoBlobs());
  const PinholeCamera k = twoBlobsCamera();
  const CameraPose camera;
  const std::vector<ModelContourPoint> all = extractOccludingContours(model.mesh(), k, camera);
  std::vector<Eigen::Vector3d> points;
  for (const ModelContourPoint& s : all)
  {
    points.push_back(s.point);
  }
  std::vector<char> visible;
  model.visibility().classify(k, camera, points, visible);

  const std::vector<ModelContourPoint> kept = visibleModelContours(model, k, camera);
  std::vector<ModelContourPoint> expected;
  for (size_t i = 0; i < all.size(); ++i)
  {
    if (visible[i])
    {
      expected.push_back(all[i]);
    }
  }
  ASSERT_EQ(kept.size(), expected.size());
  for (size_t i = 0; i < kept.size(); ++i)
  {
    EXPECT_EQ(kept[i].point, expected[i].point);
    EXPECT_EQ(kept[i].pixel, expected[i].pixel);
  }
  // The near blob hides part of the far blob's outline, never its own.
  EXPECT_LT(kept.size(), all.size());
  for (const ModelContourPoint& s : kept)
  {
    if (s.point.z() < 40.0)
    {
      continue;
    }
    // Far outline samples seen past the near blob project outside its disc.
    const Eigen::Vector2d nearCentre = k.project(Eigen::Vector3d(1.5, 0.0, 30.0));
    EXPECT_GT((s.pixel - nearCentre).norm(), 300.0 * 3.0 / 30.0 * 0.95);
  }
}

TEST(VisibleModelContours, AddsTheTimeOfBothStages)
{
  const RegistrationModel model(twoBlobs());
  StageTimes times;
  times.contoursMs = 1000.0;
  visibleModelContours(model, twoBlobsCamera(), CameraPose(), OccludingContourOptions(), &times);
  EXPECT_GE(times.contoursMs, 1000.0);
  EXPECT_LT(times.contoursMs, 1000.0 + 10000.0);
  EXPECT_GE(times.visibilityMs, 0.0);
  EXPECT_EQ(times.match3dMs, 0.0);
}

TEST(VisibleModelContours, SpacingSetsTheNumberOfSamples)
{
  const RegistrationModel model(fixtures::makeSphere(3.0, 3, { 0.0, 0.0, 30.0 }, true));
  OccludingContourOptions dense;
  dense.sampleSpacingPx = 0.5;
  OccludingContourOptions sparse;
  sparse.sampleSpacingPx = 2.0;
  const size_t many = visibleModelContours(model, twoBlobsCamera(), CameraPose(), dense).size();
  const size_t few = visibleModelContours(model, twoBlobsCamera(), CameraPose(), sparse).size();
  EXPECT_GT(static_cast<double>(many), 2.0 * static_cast<double>(few));
}
