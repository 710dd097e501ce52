// The scan of P4's synthetic patient: grids, blur, the head's position and
// noise, on volumes made in memory whose values are linear in position.
#include "ErrorMessage.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/PatientScan.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace vimlop;

namespace
{

/// A 40 x 36 x 30 volume (0.5 x 0.5 x 1 mm) whose value is a + b . x (mm).
CTVolume rampVolume(double a, const std::array<double, 3>& b)
{
  CTVolume v;
  v.dims = { 40, 36, 30 };
  v.spacingMm = { 0.5, 0.5, 1.0 };
  v.originMm = { -10.0, 5.0, 20.0 };
  v.intensities.resize(v.numberOfVoxels());
  std::size_t n = 0;
  for (int k = 0; k < v.dims[2]; ++k)
  {
    for (int j = 0; j < v.dims[1]; ++j)
    {
      for (int i = 0; i < v.dims[0]; ++i, ++n)
      {
        const std::array<double, 3> x = v.indexToPhysical({ double(i), double(j), double(k) });
        v.intensities[n] = static_cast<float>(a + b[0] * x[0] + b[1] * x[1] + b[2] * x[2]);
      }
    }
  }
  return v;
}

double valueAt(const CTVolume& v, int i, int j, int k)
{
  return v.intensities[static_cast<std::size_t>(i) +
    static_cast<std::size_t>(v.dims[0]) * (j + static_cast<std::size_t>(v.dims[1]) * k)];
}

} // namespace

TEST(PatientScan, TheTemplatesScanGivesTheHeadBack)
{
  const CTVolume head = rampVolume(100.0, { 2.0, -3.0, 5.0 });
  const PatientScanOptions same;
  EXPECT_TRUE(same.isTemplateGrid());
  const CTVolume patient = PatientScan(head, same).scan(head, 0.0, 1u);
  ASSERT_EQ(patient.dims, head.dims);
  for (std::size_t n = 0; n < head.intensities.size(); n += 97)
  {
    EXPECT_NEAR(patient.intensities[n], head.intensities[n], 1e-3);
  }
}

TEST(PatientScan, ThickerSlicesAndLargerPixelsResampleTheSameExtent)
{
  // A ramp survives the blur (away from the clamped edges) and the resampling.
  const CTVolume head = rampVolume(0.0, { 1.0, 2.0, 4.0 });
  PatientScanOptions o;
  o.pixelSpacingMm = 0.8;
  o.sliceSpacingMm = 2.5;
  o.blurMm = 0.4;
  EXPECT_FALSE(o.isTemplateGrid());
  const CTVolume patient = PatientScan(head, o).scan(head, 0.0, 1u);
  EXPECT_EQ(patient.dims, (std::array<int, 3>{ 25, 22, 12 })); // 19.5 / 0.8, 17.5 / 0.8, 29 / 2.5
  EXPECT_EQ(patient.spacingMm, (std::array<double, 3>{ 0.8, 0.8, 2.5 }));
  EXPECT_EQ(patient.originMm, head.originMm);
  const std::array<double, 3> x = patient.indexToPhysical({ 12.0, 11.0, 6.0 });
  EXPECT_NEAR(valueAt(patient, 12, 11, 6), x[0] + 2.0 * x[1] + 4.0 * x[2], 1e-2);
}

TEST(PatientScan, TheHeadTurnsAboutTheGridsCentreAndMoves)
{
  const CTVolume head = rampVolume(0.0, { 0.0, 1.0, 0.0 }); // the value is y
  PatientScanOptions o;
  o.rotationDeg = 10.0;
  o.shiftMm = { 1.0, -2.0, 1.5 };
  const PatientScan scan(head, o);
  const std::array<double, 3> centre = head.indexToPhysical({ 19.5, 17.5, 14.5 });
  const std::array<double, 3> placed = scan.place(centre);
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(placed[a], centre[a] + o.shiftMm[a], 1e-9);
  }
  // A point 5 mm above the centre turns by 10 degrees about the x axis.
  const std::array<double, 3> above = scan.place({ centre[0], centre[1], centre[2] + 5.0 });
  EXPECT_NEAR(above[1] - placed[1], -5.0 * std::sin(10.0 * M_PI / 180.0), 1e-9);
  EXPECT_NEAR(above[2] - placed[2], 5.0 * std::cos(10.0 * M_PI / 180.0), 1e-9);
  // The patient's voxel at y holds the head's value at M^-1(y).
  const CTVolume patient = scan.scan(head, 0.0, 1u);
  const std::array<double, 3> y = patient.indexToPhysical({ 20.0, 18.0, 15.0 });
  const double a = 10.0 * M_PI / 180.0;
  const double expectedY = centre[1] + std::cos(a) * (y[1] - centre[1] - o.shiftMm[1]) +
    std::sin(a) * (y[2] - centre[2] - o.shiftMm[2]);
  EXPECT_NEAR(valueAt(patient, 20, 18, 15), expectedY, 1e-3);
  // Where the moved head leaves the field of view, the scan sees air.
  EXPECT_EQ(valueAt(patient, 0, 0, 0), -1000.0);
}

TEST(PatientScan, AddsNoiseOfTheRequestedSpreadLast)
{
  const CTVolume head = rampVolume(0.0, { 1.0, 0.0, 0.0 });
  PatientScanOptions o;
  o.sliceSpacingMm = 2.0;
  const PatientScan scan(head, o);
  const CTVolume clean = scan.scan(head, 0.0, 1u);
  const CTVolume noisy = scan.scan(head, 25.0, 7u);
  double sum = 0.0, squares = 0.0;
  for (std::size_t n = 0; n < clean.intensities.size(); ++n)
  {
    const double e = noisy.intensities[n] - clean.intensities[n];
    sum += e;
    squares += e * e;
  }
  const double count = static_cast<double>(clean.intensities.size());
  EXPECT_NEAR(sum / count, 0.0, 1.0);
  EXPECT_NEAR(std::sqrt(squares / count), 25.0, 1.0);
  EXPECT_EQ(scan.scan(head, 25.0, 7u).intensities, noisy.intensities) << "the same seed";
}

TEST(PatientScan, RefusesValuesOutOfRangeAndAHeadOnAnotherGrid)
{
  PatientScanOptions o;
  o.rotationDeg = 40.0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "patient scan: rotation (-30 to 30 deg) 40 is out of range");
  o = PatientScanOptions();
  o.sliceSpacingMm = 0.05;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "patient scan: slice spacing (0 or 0.1-10 mm) 0.05 is out of range");
  o = PatientScanOptions();
  o.shiftMm = { 0.0, 60.0, 0.0 };
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "patient scan: shift (-50 to 50 mm per axis) 60 is out of range");
  o = PatientScanOptions();
  o.blurMm = -1.0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "patient scan: blur (0-5 mm) -1 is out of range");
  const CTVolume head = rampVolume(0.0, { 1.0, 0.0, 0.0 });
  CTVolume other = head;
  other.dims[2] = 10;
  other.intensities.resize(other.numberOfVoxels());
  EXPECT_EQ(
    fixtures::errorMessageOf([&] { PatientScan(head, PatientScanOptions()).scan(other, 0.0, 1u); }),
    "the head to scan does not match the scan's template grid");
}
