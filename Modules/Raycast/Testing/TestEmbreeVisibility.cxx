#include "TestMeshes.h"
#include <vimlop/Core/MeshTreeVisibility.h>
#include <vimlop/Core/OccludingContours.h>
#include <vimlop/Core/Registration.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Raycast/EmbreeVisibility.h>

#include <gtest/gtest.h>

#include <random>

using namespace vimlop;

TEST(EmbreeVisibility, AgreesWithTheExactReferenceOnContourSamples)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  auto scene = std::make_shared<EmbreeScene>(mesh);
  const EmbreeVisibility embree(scene);
  const MeshTreeVisibility reference(std::make_shared<MeshTree>(mesh));
  const PinholeCamera k = PinholeCamera::simulatedEndoscope();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-8.0, 8.0);
  size_t total = 0;
  size_t agree = 0;
  size_t hidden = 0;
  for (int view = 0; view < 20; ++view)
  {
    const Eigen::Vector3d centre(u(rng), u(rng), u(rng));
    const CameraPose camera = CameraPose::lookAt(centre, { 8, 0, 3 }, { 0, 0, 1 });
    const auto samples = extractOccludingContours(mesh, k, camera);
    std::vector<Eigen::Vector3d> points;
    for (const auto& s : samples)
    {
      points.push_back(s.point);
    }
    std::vector<char> a, b;
    embree.classify(k, camera, points, a);
    reference.classify(k, camera, points, b);
    for (size_t i = 0; i < points.size(); ++i)
    {
      agree += a[i] == b[i];
      hidden += b[i] == 0;
    }
    total += points.size();
  }
  ASSERT_GT(total, 1000u);
  EXPECT_GT(hidden, total / 50); // the blobs hide part of the cavity's contours
  EXPECT_GE(static_cast<double>(agree), 0.995 * total);
}

TEST(EmbreeVisibility, RegistrationWithEmbreeBackendsMatchesCore)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  const RegistrationModel core(mesh);
  const RegistrationModel embree = makeEmbreeRegistrationModel(mesh);
  SyntheticOptions synthetic;
  synthetic.points = 300;
  const SyntheticTrial trial = makeSyntheticTrial(core, synthetic, 11);
  RegistrationOptions options;
  options.minScale = 0.8;
  options.maxScale = 1.25;
  const RegistrationResult a = registerVideo(core, trial.data, trial.initialSfmToCT, options);
  const RegistrationResult b = registerVideo(embree, trial.data, trial.initialSfmToCT, options);
  // The backends differ in a few grazing rays, hence in a few matches: the
  // results agree to within the accuracy of the registration itself.
  const double treCore = targetRegistrationError(a.sfmToCT, trial.truthSfmToCT, trial.targetsCT);
  const double treEmbree = targetRegistrationError(b.sfmToCT, trial.truthSfmToCT, trial.targetsCT);
  EXPECT_LT(treCore, 0.5);
  EXPECT_LT(treEmbree, 0.5);
  EXPECT_LT(std::abs(treCore - treEmbree), 0.1);
}
