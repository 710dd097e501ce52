#include "AirwayPhantom.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/SyntheticDeformation.h>
#include <vimlop/Imaging/TemplateRegistration.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace vimlop;
using fixtures::HeadPhantom;

namespace
{

using Point = std::array<double, 3>;

double distance(const Point& a, const Point& b)
{
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

/// Points on and around the phantom's airway box (template frame; index = mm).
std::vector<Point> airwayPoints()
{
  std::vector<Point> points;
  const auto& b = HeadPhantom::kAirwayBox;
  for (double x : { b[0] - 0.5, 0.5 * (b[0] + b[1]), b[1] + 0.5 })
  {
    for (double y : { b[2] - 0.5, 0.5 * (b[2] + b[3]), b[3] + 0.5 })
    {
      for (double z : { b[4] - 0.5, 0.5 * (b[4] + b[5]), b[5] + 0.5 })
      {
        points.push_back({ x, y, z });
      }
    }
  }
  return points;
}

} // namespace

TEST(SyntheticDeformation, HasTheRequestedSizeAndAnExactInverse)
{
  const CTVolume ct = HeadPhantom::make();
  SyntheticDeformationOptions options;
  options.maxDisplacementMm = 3.0;
  options.controlSpacingMm = 16.0;
  options.seed = 5;
  options.regionMm = { 20.0, 44.0, 30.0, 56.0, 10.0, 30.0 };
  const SyntheticDeformation d(ct, options);
  EXPECT_NEAR(d.largestDisplacementMm(), 3.0, 1e-12);
  // The largest |b| over the region's voxels is 3 mm: none above, one at it.
  double largest = 0.0;
  for (int k = 10; k <= 30; ++k)
  {
    for (int j = 30; j <= 56; ++j)
    {
      for (int i = 20; i <= 44; ++i)
      {
        const Point b = d.patientToTemplateDisplacement({ double(i), double(j), double(k) });
        largest = std::max(largest, std::hypot(b[0], b[1], b[2]));
      }
    }
  }
  EXPECT_NEAR(largest, 3.0, 1e-9);
  // templateToPatient inverts y -> y + b(y).
  for (const Point& x : airwayPoints())
  {
    const Point y = d.templateToPatient(x);
    const Point b = d.patientToTemplateDisplacement(y);
    EXPECT_LT(distance({ y[0] + b[0], y[1] + b[1], y[2] + b[2] }, x), 1e-6);
  }
  // The same seed gives the same field; another seed another one.
  const SyntheticDeformation same(ct, options);
  options.seed = 6;
  const SyntheticDeformation other(ct, options);
  const Point p{ 31.0, 44.0, 19.5 };
  EXPECT_EQ(d.patientToTemplateDisplacement(p), same.patientToTemplateDisplacement(p));
  EXPECT_GT(
    distance(d.patientToTemplateDisplacement(p), other.patientToTemplateDisplacement(p)), 1e-3);

  options.controlSpacingMm = 1.0;
  EXPECT_THROW(SyntheticDeformation(ct, options), Error);
  options.controlSpacingMm = 16.0;
  options.maxDisplacementMm = -1.0;
  EXPECT_THROW(SyntheticDeformation(ct, options), Error);
}

TEST(SyntheticDeformation, MakesThePatientByResamplingThroughTheField)
{
  const CTVolume ct = HeadPhantom::make();
  SyntheticDeformationOptions options;
  options.maxDisplacementMm = 2.5;
  options.controlSpacingMm = 20.0;
  const SyntheticDeformation d(ct, options);
  const CTVolume clean = d.makePatient(ct, 0.0, 1);
  EXPECT_EQ(clean.dims, ct.dims);
  // Far from edges, a patient voxel holds the template value at y + b(y):
  // the middle of the airway stays air, the middle of the brain stays tissue.
  const auto at = [](const CTVolume& v, int i, int j, int k)
  { return v.intensities[static_cast<std::size_t>(i + 64 * (j + 64 * k))]; };
  EXPECT_EQ(at(clean, 32, 44, 19), fixtures::kAirHU);
  EXPECT_EQ(at(clean, 32, 25, 30), fixtures::kSoftTissueHU);
  // Noise: zero mean, the requested spread, reproducible by seed.
  const CTVolume noisy = d.makePatient(ct, 20.0, 9);
  double sum = 0.0;
  double squares = 0.0;
  for (std::size_t n = 0; n < noisy.intensities.size(); ++n)
  {
    const double e = noisy.intensities[n] - clean.intensities[n];
    sum += e;
    squares += e * e;
  }
  const double count = static_cast<double>(noisy.intensities.size());
  EXPECT_NEAR(sum / count, 0.0, 0.5);
  EXPECT_NEAR(std::sqrt(squares / count), 20.0, 0.5);
  EXPECT_EQ(d.makePatient(ct, 20.0, 9).intensities, noisy.intensities);
}

class TemplateRegistrationMetrics : public ::testing::TestWithParam<TemplateRegistrationMetric>
{
};

TEST_P(TemplateRegistrationMetrics, RecoverAKnownDeformationOfThePhantom)
{
  const CTVolume ct = HeadPhantom::make();
  SyntheticDeformationOptions deformation;
  deformation.maxDisplacementMm = 3.0;
  deformation.controlSpacingMm = 24.0;
  deformation.seed = 3;
  const SyntheticDeformation d(ct, deformation);
  const CTVolume patient = d.makePatient(ct, 10.0, 11);

  TemplateRegistrationOptions options;
  const auto& box = HeadPhantom::kAirwayBox;
  options.regionMm = { double(box[0]), double(box[1]), double(box[2]), double(box[3]),
    double(box[4]), double(box[5]) };
  options.marginMm = 10.0;
  // The phantom is small: finer levels than the CT defaults.
  options.affineLevelSpacingMm = { 2.0, 1.0 };
  options.synLevelSpacingMm = { 2.0, 1.0 };
  options.synIterations = { 30, 20 };
  options.metric = GetParam();
  double last = -1.0;
  bool monotone = true;
  const TemplateRegistration r = TemplateRegistration::compute(ct, patient, options,
    [&](double fraction, const std::string&)
    {
      monotone = monotone && fraction >= last;
      last = fraction;
    });
  EXPECT_TRUE(monotone);
  EXPECT_EQ(last, 1.0);
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(r.settings.metric, GetParam());
  EXPECT_EQ(r.settings.synIterations, options.synIterations);
  EXPECT_DOUBLE_EQ(r.overlapFraction, 1.0);
  EXPECT_GT(r.finalCorrelation, r.initialCorrelation);
  EXPECT_GT(r.finalCorrelation, 0.9);
  // The template crop is the region plus the margin, within the CT.
  EXPECT_DOUBLE_EQ(r.templateCropMm[0], box[0] - 10.0);
  EXPECT_DOUBLE_EQ(r.templateCropMm[5], box[5] + 10.0);
  ASSERT_TRUE(r.templateToPatient.isValid());
  ASSERT_TRUE(r.patientToTemplate.isValid());

  double before = 0.0;
  double after = 0.0;
  double roundTrip = 0.0;
  const std::vector<Point> points = airwayPoints();
  for (const Point& x : points)
  {
    const Point truth = d.templateToPatient(x);
    const Point y = r.templateToPatient.transformPoint(x);
    before += distance(x, truth) / points.size();
    after += distance(y, truth) / points.size();
    roundTrip += distance(r.patientToTemplate.transformPoint(y), x) / points.size();
  }
  std::printf(
    "phantom, metric %d: before %.2f mm, after %.2f mm, round trip %.2f mm, correlation %.3f\n",
    static_cast<int>(GetParam()), before, after, roundTrip, r.finalCorrelation);
  EXPECT_GT(before, 1.0);
  EXPECT_LT(after, 0.5);
  EXPECT_LT(roundTrip, 0.3);
}

// Mutual information, the default, and ANTs' neighbourhood correlation.
INSTANTIATE_TEST_SUITE_P(SyN, TemplateRegistrationMetrics,
  ::testing::Values(TemplateRegistrationMetric::MattesMutualInformation,
    TemplateRegistrationMetric::NeighborhoodCorrelation));

TEST(TemplateRegistration, RecoversAKnownDeformationOfThePhantomWithABSplineStage)
{
  // The B-spline stage alone (SyN given no iterations): its field and the
  // numerical inverse of it carry the phantom's airway to the truth and back.
  const CTVolume ct = HeadPhantom::make();
  SyntheticDeformationOptions deformation;
  deformation.maxDisplacementMm = 3.0;
  deformation.controlSpacingMm = 24.0;
  deformation.seed = 3;
  const SyntheticDeformation d(ct, deformation);
  const CTVolume patient = d.makePatient(ct, 10.0, 11);

  TemplateRegistrationOptions options;
  const auto& box = HeadPhantom::kAirwayBox;
  options.regionMm = { double(box[0]), double(box[1]), double(box[2]), double(box[3]),
    double(box[4]), double(box[5]) };
  options.marginMm = 10.0;
  options.affineLevelSpacingMm = { 2.0, 1.0 };
  options.bsplineGridMm = { 24.0, 12.0 };
  options.bsplineLevelSpacingMm = { 2.0, 1.0 };
  options.bsplineIterations = { 30, 30 };
  options.bsplineSamplingFraction = 0.2;
  options.synLevelSpacingMm = { 2.0 };
  options.synIterations = { 0 };
  double last = -1.0;
  bool monotone = true;
  const TemplateRegistration r = TemplateRegistration::compute(ct, patient, options,
    [&](double fraction, const std::string&)
    {
      monotone = monotone && fraction >= last;
      last = fraction;
    });
  EXPECT_TRUE(monotone);
  EXPECT_EQ(last, 1.0);
  EXPECT_GT(r.bsplineSeconds, 0.0);
  EXPECT_EQ(r.settings.bsplineGridMm, options.bsplineGridMm);

  double before = 0.0;
  double after = 0.0;
  double roundTrip = 0.0;
  const std::vector<Point> points = airwayPoints();
  for (const Point& x : points)
  {
    const Point truth = d.templateToPatient(x);
    const Point y = r.templateToPatient.transformPoint(x);
    before += distance(x, truth) / points.size();
    after += distance(y, truth) / points.size();
    roundTrip += distance(r.patientToTemplate.transformPoint(y), x) / points.size();
  }
  std::printf("phantom, B-spline stage: before %.2f mm, after %.2f mm, round trip %.2f mm\n",
    before, after, roundTrip);
  EXPECT_GT(before, 1.0);
  EXPECT_LT(after, 0.5);
  EXPECT_LT(roundTrip, 0.3);
}
