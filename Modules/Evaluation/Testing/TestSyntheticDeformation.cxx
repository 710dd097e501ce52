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

/// The phantom, a known 3 mm deformation of it (the patient), options that
/// suit its size, and how far a registration carries its airway.
class PhantomDeformation
{
public:
  const CTVolume ct = HeadPhantom::make();
  const SyntheticDeformation truth{ ct, deformationOptions() };
  const CTVolume patient = truth.makePatient(ct, 10.0, 11);

  /// The airway box plus 10 mm; finer affine levels than the CT defaults.
  static TemplateRegistrationOptions options()
  {
    TemplateRegistrationOptions o;
    const auto& box = HeadPhantom::kAirwayBox;
    o.regionMm = { double(box[0]), double(box[1]), double(box[2]), double(box[3]), double(box[4]),
      double(box[5]) };
    o.marginMm = 10.0;
    o.affineLevelSpacingMm = { 2.0, 1.0 };
    return o;
  }

  /// Registers the phantom to the patient, expecting progress that never goes back and ends at 1.
  TemplateRegistration registered(const TemplateRegistrationOptions& o) const
  {
    double last = -1.0;
    bool monotone = true;
    TemplateRegistration r = TemplateRegistration::compute(ct, patient, o,
      [&](double fraction, const std::string&)
      {
        monotone = monotone && fraction >= last;
        last = fraction;
      });
    EXPECT_TRUE(monotone);
    EXPECT_EQ(last, 1.0);
    return r;
  }

  /// Mean distances over the airway points (mm): before registration, after
  /// it, and of the round trip template -> patient -> template.
  struct Recovery
  {
    double before = 0.0;
    double after = 0.0;
    double roundTrip = 0.0;
  };
  Recovery recovery(const TemplateRegistration& r) const
  {
    Recovery m;
    const std::vector<Point> points = airwayPoints();
    for (const Point& x : points)
    {
      const Point y = r.templateToPatient.transformPoint(x);
      m.before += distance(x, truth.templateToPatient(x)) / points.size();
      m.after += distance(y, truth.templateToPatient(x)) / points.size();
      m.roundTrip += distance(r.patientToTemplate.transformPoint(y), x) / points.size();
    }
    return m;
  }

private:
  static SyntheticDeformationOptions deformationOptions()
  {
    SyntheticDeformationOptions o;
    o.maxDisplacementMm = 3.0;
    o.controlSpacingMm = 24.0;
    o.seed = 3;
    return o;
  }
};

class TemplateRegistrationMetrics : public ::testing::TestWithParam<TemplateRegistrationMetric>
{
};

TEST_P(TemplateRegistrationMetrics, RecoverAKnownDeformationOfThePhantom)
{
  const PhantomDeformation phantom;
  TemplateRegistrationOptions options = PhantomDeformation::options();
  // SyN alone (no B-spline stage before it). The phantom is small: finer
  // levels than the CT defaults.
  options.bsplineGridMm.clear();
  options.synLevelSpacingMm = { 2.0, 1.0 };
  options.synIterations = { 30, 20 };
  options.metric = GetParam();
  const TemplateRegistration r = phantom.registered(options);
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(r.settings.metric, GetParam());
  EXPECT_EQ(r.settings.synIterations, options.synIterations);
  EXPECT_DOUBLE_EQ(r.overlapFraction, 1.0);
  EXPECT_GT(r.finalCorrelation, r.initialCorrelation);
  EXPECT_GT(r.finalCorrelation, 0.9);
  // The template crop is the region plus the margin, within the CT.
  EXPECT_DOUBLE_EQ(r.templateCropMm[0], HeadPhantom::kAirwayBox[0] - 10.0);
  EXPECT_DOUBLE_EQ(r.templateCropMm[5], HeadPhantom::kAirwayBox[5] + 10.0);
  ASSERT_TRUE(r.templateToPatient.isValid());
  ASSERT_TRUE(r.patientToTemplate.isValid());

  const PhantomDeformation::Recovery m = phantom.recovery(r);
  std::printf(
    "phantom, metric %d: before %.2f mm, after %.2f mm, round trip %.2f mm, correlation %.3f\n",
    static_cast<int>(GetParam()), m.before, m.after, m.roundTrip, r.finalCorrelation);
  EXPECT_GT(m.before, 1.0);
  EXPECT_LT(m.after, 0.5);
  EXPECT_LT(m.roundTrip, 0.3);
}

// Mutual information, the default, and ANTs' neighbourhood correlation.
INSTANTIATE_TEST_SUITE_P(SyN, TemplateRegistrationMetrics,
  ::testing::Values(TemplateRegistrationMetric::MattesMutualInformation,
    TemplateRegistrationMetric::NeighborhoodCorrelation),
  [](const ::testing::TestParamInfo<TemplateRegistrationMetric>& info)
  { return templateRegistrationMetricName(info.param); });

TEST(TemplateRegistration, RecoversAKnownDeformationOfThePhantomWithABSplineStage)
{
  // The B-spline stage alone (SyN given no iterations): its field and the
  // numerical inverse of it carry the phantom's airway to the truth and back.
  const PhantomDeformation phantom;
  TemplateRegistrationOptions options = PhantomDeformation::options();
  options.bsplineGridMm = { 24.0, 12.0 };
  options.bsplineLevelSpacingMm = { 2.0, 1.0 };
  options.bsplineIterations = { 30, 30 };
  options.bsplineSamplingFraction = 0.2;
  options.synLevelSpacingMm = { 2.0 };
  options.synIterations = { 0 };
  const TemplateRegistration r = phantom.registered(options);
  EXPECT_GT(r.bsplineSeconds, 0.0);
  EXPECT_EQ(r.settings.bsplineGridMm, options.bsplineGridMm);

  const PhantomDeformation::Recovery m = phantom.recovery(r);
  std::printf("phantom, B-spline stage: before %.2f mm, after %.2f mm, round trip %.2f mm\n",
    m.before, m.after, m.roundTrip);
  EXPECT_GT(m.before, 1.0);
  EXPECT_LT(m.after, 0.5);
  EXPECT_LT(m.roundTrip, 0.3);
}
