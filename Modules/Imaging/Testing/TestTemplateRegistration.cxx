#include "AirwayPhantom.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/TemplateRegistration.h>
#include <vimlop/Imaging/VolumeCrop.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

using namespace vimlop;
using fixtures::HeadPhantom;

namespace
{

std::string registrationError(
  const CTVolume& a, const CTVolume& b, const TemplateRegistrationOptions& options)
{
  try
  {
    TemplateRegistration::compute(a, b, options);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(TemplateRegistration, WarnsWithTheCorrelationWhenNothingMatches)
{
  // A "patient" of pure noise on the phantom's grid: the images overlap, the
  // registration runs, and the result is flagged as poor.
  const CTVolume ct = HeadPhantom::make();
  CTVolume noise = ct;
  std::uint32_t state = 12345u;
  for (float& v : noise.intensities)
  {
    state = state * 1664525u + 1013904223u; // a fixed linear congruential sequence
    v = static_cast<float>(state >> 20) - 2000.0f;
  }
  TemplateRegistrationOptions options;
  const auto& box = HeadPhantom::kAirwayBox;
  options.regionMm = { double(box[0]), double(box[1]), double(box[2]), double(box[3]),
    double(box[4]), double(box[5]) };
  options.synLevelSpacingMm = { 4.0, 2.0 };
  options.synIterations = { 5, 3 };
  const TemplateRegistration r = TemplateRegistration::compute(ct, noise, options);
  EXPECT_LT(std::abs(r.finalCorrelation), 0.3);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0].rfind("the registration may be poor: the correlation of template and "
                                "patient intensities is ",
              0),
    0u)
    << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("Mattes mutual information"), std::string::npos);
}

TEST(TemplateRegistration, RefusesImagesThatDoNotOverlap)
{
  const CTVolume ct = HeadPhantom::make();
  TemplateRegistrationOptions options;
  const auto& box = HeadPhantom::kAirwayBox;
  options.regionMm = { double(box[0]), double(box[1]), double(box[2]), double(box[3]),
    double(box[4]), double(box[5]) };
  // The patient CT holds only the top of the head: no nose to match.
  const CTVolume top = cropVolume(ct, { 0.0, 63.0, 0.0, 63.0, 40.0, 47.0 });
  const std::string message = registrationError(ct, top, options);
  EXPECT_EQ(
    message.rfind("template and patient CT do not overlap after the affine registration: ", 0), 0u)
    << message;
  EXPECT_NE(message.find("% of the template's region maps into the patient CT"), std::string::npos);

  TemplateRegistrationOptions empty = options;
  empty.regionMm = { 1.0, 0.0, 0.0, 1.0, 0.0, 1.0 };
  EXPECT_EQ(registrationError(ct, ct, empty), "the region to register is empty");
  TemplateRegistrationOptions away = options;
  away.regionMm = { 500.0, 510.0, 0.0, 10.0, 0.0, 10.0 };
  away.marginMm = 0.0;
  EXPECT_EQ(registrationError(ct, ct, away), "the region to register lies outside the template CT");
  TemplateRegistrationOptions levels = options;
  levels.synIterations = { 10 };
  EXPECT_EQ(registrationError(ct, ct, levels).rfind("registration options:", 0), 0u);
  TemplateRegistrationOptions bspline = options;
  bspline.bsplineGridMm = { 20.0, 10.0 };
  bspline.bsplineLevelSpacingMm = { 2.0 };
  bspline.bsplineIterations = { 10, 10 };
  EXPECT_EQ(registrationError(ct, ct, bspline).rfind("registration options: each stage", 0), 0u);
  bspline.bsplineLevelSpacingMm = { 2.0, 1.0 };
  bspline.bsplineSamplingFraction = 0.0;
  EXPECT_EQ(registrationError(ct, ct, bspline).rfind("registration options out of range", 0), 0u);
  CTVolume flat = fixtures::emptyVolume({ 64, 64, 1 });
  EXPECT_EQ(registrationError(ct, flat, options),
    "the patient CT is not a 3-D volume (64 x 64 x 1 voxels)");
}

TEST(TemplateRegistration, NamesEachSyNMetricAndRefusesUnknownNames)
{
  for (const TemplateRegistrationMetric metric :
    { TemplateRegistrationMetric::MattesMutualInformation, TemplateRegistrationMetric::MeanSquares,
      TemplateRegistrationMetric::NeighborhoodCorrelation })
  {
    EXPECT_EQ(templateRegistrationMetricFromName(templateRegistrationMetricName(metric)), metric);
  }
  EXPECT_EQ(
    templateRegistrationMetricName(TemplateRegistrationMetric::NeighborhoodCorrelation), "cc");
  try
  {
    templateRegistrationMetricFromName("ncc");
    FAIL() << "an unknown metric was accepted";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "unknown SyN metric 'ncc' (mi, ms or cc)");
  }
}

TEST(TemplateRegistration, GivesTheSameMapOnEveryRunOfTheSamePair)
{
  // A lab that registers a patient twice must get the same model twice. The
  // patient is the phantom moved by one voxel and a half, so the affine
  // stage has work to do on every thread.
  const CTVolume ct = HeadPhantom::make();
  CTVolume patient = ct;
  patient.originMm[0] += 1.5;
  patient.originMm[2] -= 1.5;
  TemplateRegistrationOptions options;
  const auto& box = HeadPhantom::kAirwayBox;
  options.regionMm = { double(box[0]), double(box[1]), double(box[2]), double(box[3]),
    double(box[4]), double(box[5]) };
  options.affineLevelSpacingMm = { 2.0, 1.0 };
  options.affineSamplingFraction = 1.0;
  options.bsplineGridMm = { 10.0 };
  options.bsplineLevelSpacingMm = { 1.0 };
  options.bsplineIterations = { 5 };
  const TemplateRegistration first = TemplateRegistration::compute(ct, patient, options);
  for (int run = 0; run < 3; ++run)
  {
    const TemplateRegistration again = TemplateRegistration::compute(ct, patient, options);
    EXPECT_EQ(again.affine, first.affine) << "run " << run;
    EXPECT_EQ(again.templateToPatient.displacements, first.templateToPatient.displacements)
      << "run " << run;
  }
}
