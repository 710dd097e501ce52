#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/Registration.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/SyntheticExperiment.h>

#include <gtest/gtest.h>

using namespace vimlop;

namespace
{

const RegistrationModel& cavityModel()
{
  static const RegistrationModel model(fixtures::makeCavityWithBlobs());
  return model;
}

SyntheticOptions syntheticOptions()
{
  SyntheticOptions o;
  o.points = 400; // a smaller model than an airway needs fewer
  return o;
}

RegistrationOptions optionsFor(RegistrationMethod method)
{
  RegistrationOptions o;
  o.method = method;
  o.minScale = 0.8;
  o.maxScale = 1.25;
  return o;
}

} // namespace

TEST(Registration, RecoversTheSyntheticMisalignment)
{
  const RegistrationModel& model = cavityModel();
  int vimlopBetter = 0;
  for (std::uint64_t seed : { 1u, 2u, 3u })
  {
    const SyntheticTrial trial = makeSyntheticTrial(model, syntheticOptions(), seed);
    const double before =
      targetRegistrationError(trial.initialSfmToCT, trial.truthSfmToCT, trial.targetsCT);
    EXPECT_GT(before, 1.0);
    const RegistrationResult vimlop = registerVideo(
      model, trial.data, trial.initialSfmToCT, optionsFor(RegistrationMethod::VIMLOP));
    const RegistrationResult imlp =
      registerVideo(model, trial.data, trial.initialSfmToCT, optionsFor(RegistrationMethod::IMLP));
    const double treVimlop =
      targetRegistrationError(vimlop.sfmToCT, trial.truthSfmToCT, trial.targetsCT);
    const double treImlp =
      targetRegistrationError(imlp.sfmToCT, trial.truthSfmToCT, trial.targetsCT);
    EXPECT_LT(treVimlop, 0.5) << "seed " << seed << ", TRE before " << before;
    EXPECT_TRUE(vimlop.termination == TerminationReason::Converged ||
      vimlop.termination == TerminationReason::Stalled)
      << toString(vimlop.termination) << " after " << vimlop.iterations << " iterations, TRE "
      << treVimlop << " IMLP " << treImlp << " time " << vimlop.runtimeSeconds;

    vimlopBetter += treVimlop < treImlp;
    // The registered cameras are close to the truth.
    for (size_t c = 0; c < trial.trueCamerasCT.size(); ++c)
    {
      EXPECT_LT(cameraPositionError(vimlop.frames[c].cameraToCT, trial.trueCamerasCT[c]), 1.0);
    }
    // Result fields are filled consistently.
    EXPECT_EQ(vimlop.pointInliers.size(), trial.data.points.size());
    EXPECT_EQ(vimlop.history.size(), static_cast<size_t>(vimlop.iterations));
    EXPECT_LT(vimlop.residualErrorMm, 1.0);
    EXPECT_GT(vimlop.contourErrorPx, 0.0);
    EXPECT_LE(vimlop.contourErrorInliersPx, vimlop.contourErrorPx);
    // The baseline's contours are measured too (for comparisons and multi-starts).
    EXPECT_GT(imlp.contourErrorPx, 0.0);
    EXPECT_GT(imlp.frames[0].matched, 0);
  }
  EXPECT_GE(vimlopBetter, 2);
}

TEST(Registration, TrimmedICPBaselineRuns)
{
  const RegistrationModel& model = cavityModel();
  const SyntheticTrial trial = makeSyntheticTrial(model, syntheticOptions(), 4);
  const RegistrationResult icp = registerVideo(
    model, trial.data, trial.initialSfmToCT, optionsFor(RegistrationMethod::TrimmedICP));
  const double before =
    targetRegistrationError(trial.initialSfmToCT, trial.truthSfmToCT, trial.targetsCT);
  EXPECT_LT(targetRegistrationError(icp.sfmToCT, trial.truthSfmToCT, trial.targetsCT), before);
}

TEST(Registration, ResultsDoNotDependOnTheThreadCount)
{
  const RegistrationModel& model = cavityModel();
  const SyntheticTrial trial = makeSyntheticTrial(model, syntheticOptions(), 5);
  RegistrationOptions one = optionsFor(RegistrationMethod::VIMLOP);
  one.threads = 1;
  RegistrationOptions two = one;
  two.threads = 2;
  const RegistrationResult a = registerVideo(model, trial.data, trial.initialSfmToCT, one);
  const RegistrationResult b = registerVideo(model, trial.data, trial.initialSfmToCT, two);
  EXPECT_EQ(a.sfmToCT.matrix(), b.sfmToCT.matrix());
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.pointInliers, b.pointInliers);
  EXPECT_EQ(a.contourErrorPx, b.contourErrorPx);
}

TEST(Registration, CallbackSeesEveryIterationAndCanCancel)
{
  const RegistrationModel& model = cavityModel();
  const SyntheticTrial trial = makeSyntheticTrial(model, syntheticOptions(), 6);
  int calls = 0;
  const RegistrationResult result =
    registerVideo(model, trial.data, trial.initialSfmToCT, optionsFor(RegistrationMethod::VIMLOP),
      [&](const IterationRecord& record)
      {
        EXPECT_EQ(record.iteration, calls + 1);
        EXPECT_GT(record.pointInliers, 0);
        return ++calls < 3;
      });
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(result.termination, TerminationReason::Cancelled);
  EXPECT_EQ(result.iterations, 3);
}

TEST(Registration, CallbackSeesTheIterationsThatEndAStage)
{
  // A stall ends a stage without an update; observers still hear of it, so
  // that progress bars and vtkVIMLOPRegistration's IterationEvent count every
  // iteration of the history.
  const RegistrationModel& model = cavityModel();
  const SyntheticTrial trial = makeSyntheticTrial(model, syntheticOptions(), 7);
  RegistrationOptions options = optionsFor(RegistrationMethod::VIMLOP);
  options.stallIterations = 2;
  options.stallRelativeDecrease = 0.5; // every stage stalls after two iterations
  int calls = 0;
  const RegistrationResult result = registerVideo(model, trial.data, trial.initialSfmToCT, options,
    [&](const IterationRecord&) { return ++calls > 0; });
  EXPECT_EQ(result.termination, TerminationReason::Stalled);
  EXPECT_EQ(calls, result.iterations);
}

TEST(Registration, AnatomicalConstraintKeepsCamerasInside)
{
  // A box cavity; the data says the floor and walls lie 3 mm lower than the
  // model's, so the best fit lifts everything by 3 mm, which would push the
  // camera, 0.5 mm under the ceiling, out of the cavity.
  const RegistrationModel model(fixtures::makeBox({ -10, -10, -10 }, { 10, 10, 10 }));
  RegistrationData data;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-9.0, 9.0);
  for (int i = 0; i < 300; ++i)
  {
    Eigen::Vector3d p(u(rng), u(rng), -10.0);
    if (i % 3 == 1)
    {
      p = Eigen::Vector3d(-10.0, u(rng), u(rng) * 0.5 - 5.0);
    }
    else if (i % 3 == 2)
    {
      p = Eigen::Vector3d(u(rng), 10.0, u(rng) * 0.5 - 5.0);
    }
    data.points.push_back(p - Eigen::Vector3d(0.0, 0.0, 3.0));
    data.pointCovariances.push_back(0.04 * Eigen::Matrix3d::Identity());
  }
  VideoFrame frame;
  frame.intrinsics = PinholeCamera::simulatedEndoscope();
  frame.cameraToSfm = CameraPose::lookAt({ 0, 0, 9.5 }, { 0, 0, 0 }, { 0, 1, 0 });
  data.frames.push_back(frame);

  RegistrationOptions options = optionsFor(RegistrationMethod::IMLP);
  options.trimFraction = 0.0;
  // Scaling about the corner of the walls would fit these points too; fix s.
  options.minScale = options.maxScale = 1.0;
  const RegistrationResult constrained = registerVideo(model, data, SimilarityTransform(), options);
  const double z = constrained.frames[0].cameraToCT.centre.z();

  EXPECT_LE(z, 10.0);
  EXPECT_GT(z, 9.5); // it moved up as far as the ceiling allows
  EXPECT_GT(constrained.history.front().backoffSteps + constrained.history.back().backoffSteps, 0);
  options.anatomicalConstraint = false;
  const RegistrationResult free = registerVideo(model, data, SimilarityTransform(), options);

  EXPECT_NEAR(free.frames[0].cameraToCT.centre.z(), 12.5, 0.1);
}

TEST(Registration, BadInputGetsAClearError)
{
  const RegistrationModel& model = cavityModel();
  const SyntheticTrial trial = makeSyntheticTrial(model, syntheticOptions(), 7);
  auto message = [&](const RegistrationData& data, const SimilarityTransform& initial,
                   const RegistrationOptions& o)
  {
    try
    {
      registerVideo(model, data, initial, o);
    }
    catch (const Error& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const RegistrationOptions vimlop = optionsFor(RegistrationMethod::VIMLOP);

  RegistrationData empty = trial.data;
  empty.points.clear();
  empty.pointCovariances.clear();
  EXPECT_EQ(
    message(empty, trial.initialSfmToCT, vimlop), "registration data: the point set is empty");

  RegistrationData nan = trial.data;
  nan.points[3].x() = std::nan("");
  EXPECT_EQ(
    message(nan, trial.initialSfmToCT, vimlop), "registration data: point 3 is NaN or infinite");

  RegistrationData noContours = trial.data;
  for (VideoFrame& f : noContours.frames)
  {
    f.contour.clear();
  }
  EXPECT_EQ(message(noContours, trial.initialSfmToCT, vimlop),
    "registration: no frame has contour points; V-IMLOP needs them (IMLP registers points only)");
  EXPECT_EQ(
    message(noContours, trial.initialSfmToCT, optionsFor(RegistrationMethod::IMLP)), "no error");

  RegistrationOptions bounds = vimlop;
  bounds.minScale = 2.0;
  bounds.maxScale = 1.0;
  EXPECT_EQ(message(trial.data, trial.initialSfmToCT, bounds)
              .rfind("registration options: scale bounds are invalid", 0),
    0u);

  SimilarityTransform far = trial.initialSfmToCT;
  far.translation = Eigen::Vector3d(0.0, 0.0, 200.0); // every camera far outside the cavity
  EXPECT_EQ(message(trial.data, far, vimlop).rfind("registration: the camera of frame ", 0), 0u);

  SimilarityTransform bigScale = trial.initialSfmToCT;
  bigScale.scale = 3.0;
  EXPECT_EQ(
    message(trial.data, bigScale, vimlop).rfind("registration: the initial scale 3", 0), 0u);

  EXPECT_THROW(RegistrationModel{ TriangleMesh() }, Error);
}

TEST(Registration, CavityInsideTest)
{
  const RegistrationModel& model = cavityModel();
  EXPECT_TRUE(model.isInside({ 0, 0, 0 }));
  EXPECT_FALSE(model.isInside({ 8, 0, 3 }));  // inside a blob: tissue
  EXPECT_FALSE(model.isInside({ 0, 0, 40 })); // beyond the cavity wall
  EXPECT_TRUE(model.isInside({ 8, 0, 7.5 })); // just above the blob
}

TEST(SyntheticExperiment, ThePapersContourNoiseMovesThePointsByThreePixelsAndTurnsTheNormals)
{
  const RegistrationModel& model = cavityModel();
  SyntheticOptions clean = syntheticOptions();
  SyntheticOptions noisy = clean;
  noisy.contourNoisePx = SyntheticOptions::paper().contourNoisePx;
  noisy.contourNormalKappa = SyntheticOptions::paper().contourNormalKappa;
  EXPECT_EQ(noisy.contourNoisePx, 3.0);
  EXPECT_EQ(noisy.contourNormalKappa, 200.0);
  // The same seed draws the same cameras and contour samples; only the noise differs.
  const SyntheticTrial a = makeSyntheticTrial(model, clean, 11);
  const SyntheticTrial b = makeSyntheticTrial(model, noisy, 11);
  ASSERT_EQ(a.data.frames.size(), b.data.frames.size());
  double squared = 0.0;
  double angles = 0.0;
  int n = 0;
  for (size_t f = 0; f < a.data.frames.size(); ++f)
  {
    ASSERT_EQ(a.data.frames[f].contour.size(), b.data.frames[f].contour.size());
    for (size_t i = 0; i < a.data.frames[f].contour.size(); ++i)
    {
      const ContourPoint& p = a.data.frames[f].contour[i];
      const ContourPoint& q = b.data.frames[f].contour[i];
      squared += (q.pixel - p.pixel).squaredNorm();
      angles += std::pow(std::atan2(p.normal.x() * q.normal.y() - p.normal.y() * q.normal.x(),
                           p.normal.dot(q.normal)),
        2);
      EXPECT_NEAR(q.normal.norm(), 1.0, 1e-12);
      ++n;
    }
  }
  ASSERT_GT(n, 200);
  // Two axes of 3 px: a mean squared offset of 18 px²; angles of std 1/sqrt(200) rad.
  EXPECT_NEAR(squared / n, 18.0, 3.0);
  EXPECT_NEAR(std::sqrt(angles / n), 1.0 / std::sqrt(200.0), 0.01);
  SyntheticOptions bad = clean;
  bad.contourNormalKappa = -1.0;
  try
  {
    makeSyntheticTrial(model, bad, 1);
    ADD_FAILURE() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(
      e.what(), "synthetic experiment: the contour noise and its kappa must not be negative");
  }
}
