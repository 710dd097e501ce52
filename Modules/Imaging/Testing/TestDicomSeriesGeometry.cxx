#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/DicomSeriesGeometry.h>

#include "ErrorMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace vimlop;

namespace
{

/// An axial 8 x 8 slice of 0.5 mm pixels at height z (mm), named s<index>.
DicomSliceHeader axialSlice(int index, double z)
{
  DicomSliceHeader s;
  s.file = "s" + std::to_string(index);
  s.positionMm = { -2.0, 3.0, z };
  s.hasPosition = true;
  s.orientation = { 1, 0, 0, 0, 1, 0 };
  s.hasOrientation = true;
  s.pixelSpacingMm = { 0.5, 0.5 };
  s.hasPixelSpacing = true;
  s.rows = 8;
  s.columns = 8;
  s.pixelBytes = s.expectedPixelBytes = 8 * 8 * 2;
  return s;
}

std::vector<DicomSliceHeader> stackAt(const std::vector<double>& heights)
{
  std::vector<DicomSliceHeader> slices;
  for (std::size_t k = 0; k < heights.size(); ++k)
  {
    slices.push_back(axialSlice(static_cast<int>(k), heights[k]));
  }
  return slices;
}

std::string refusal(const std::vector<DicomSliceHeader>& slices)
{
  return fixtures::errorMessageOf([&] { checkDicomSeriesGeometry(slices); });
}

/// The 20-degree gantry tilt of the issue: slices tilted about the row
/// direction while their positions climb straight up z, 2 mm a slice.
void tilt(std::vector<DicomSliceHeader>& slices, double degrees)
{
  const double a = degrees * M_PI / 180.0;
  for (DicomSliceHeader& s : slices)
  {
    s.orientation = { 1, 0, 0, 0, std::cos(a), std::sin(a) };
  }
}

} // namespace

TEST(DicomSeriesGeometry, AnEvenStackIsOrderedAlongItsNormalWhateverTheFileOrder)
{
  const DicomSeriesLayout layout = checkDicomSeriesGeometry(stackAt({ 15, 10, 20, 12.5, 17.5 }));
  EXPECT_EQ(layout.order, (std::vector<std::size_t>{ 1, 3, 0, 4, 2 }));
  EXPECT_DOUBLE_EQ(layout.sliceStepMm, 2.5);
}

TEST(DicomSeriesGeometry, AGantryTiltIsRefusedWithItsAngle)
{
  std::vector<DicomSliceHeader> slices = stackAt({ 0, 2, 4, 6 });
  tilt(slices, 20.0);
  // Slice 1 lies 2 sin 20 = 0.68 mm beside the normal, 2 cos 20 = 1.88 mm up it.
  EXPECT_EQ(refusal(slices),
    "the slices are not stacked along their normal: 's1' lies 0.68 mm beside the normal through "
    "'s0', 1.88 mm from it (a gantry tilt or shear of 20.00 degrees); a regular volume of it "
    "would misplace the anatomy: resample it onto a regular grid (--resample-irregular-series)");
  // The same orientation with positions that follow the normal is a plain oblique stack.
  for (int k = 0; k < 4; ++k)
  {
    const double a = 20.0 * M_PI / 180.0;
    slices[k].positionMm = { 0.0, -2.0 * k * std::sin(a), 2.0 * k * std::cos(a) };
  }
  EXPECT_EQ(refusal(slices), "no error");
}

TEST(DicomSeriesGeometry, MissingSlicesAreRefusedNamingTheGapAndHowManyAreMissing)
{
  EXPECT_EQ(refusal(stackAt({ 0, 1, 2, 3, 9, 10, 11 })),
    "the slices are not evenly spaced: 's3' and 's4' are 6.00 mm apart where the series steps "
    "1.00 mm (5 slices are missing); a volume with one spacing would misplace the slices beyond "
    "them: resample it onto a regular grid (--resample-irregular-series)");
  EXPECT_EQ(refusal(stackAt({ 0, 1, 2, 3.5, 4.5, 5.5 })),
    "the slices are not evenly spaced: 's2' and 's3' are 1.50 mm apart where the series steps "
    "1.00 mm; a volume with one spacing would misplace the slices beyond them: resample it onto "
    "a regular grid (--resample-irregular-series)");
  // Rounding in the decimal strings (a hundredth of the step) is not a gap.
  EXPECT_EQ(refusal(stackAt({ 0, 1.004, 2, 2.997 })), "no error");
}

TEST(DicomSeriesGeometry, TwoSlicesAtOnePositionAreRefused)
{
  EXPECT_EQ(refusal(stackAt({ 0, 1, 1, 2 })),
    "slices 's1' and 's2' lie at the same position (1.00 mm along the slice normal); a series "
    "holds each slice once");
}

TEST(DicomSeriesGeometry, MixedOrientationsAreRefused)
{
  std::vector<DicomSliceHeader> slices = stackAt({ 0, 1, 2, 3 });
  const double a = 12.0 * M_PI / 180.0;
  slices[2].orientation = { std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0 };
  EXPECT_EQ(refusal(slices),
    "the slices do not share one orientation: 's2' is turned 12.00 degrees from 's0'; one volume "
    "needs one orientation");
}

TEST(DicomSeriesGeometry, OrientationVectorsThatAreNotOrthonormalAreRefused)
{
  std::vector<DicomSliceHeader> slices = stackAt({ 0, 1, 2 });
  slices[1].orientation = { 0, 0, 0, 0, 0, 0 };
  EXPECT_EQ(refusal(slices),
    "slice 's1': its Image Orientation (Patient) (0020,0037) is not two unit vectors at right "
    "angles (row length 0.000, column length 0.000, row . column 0.000)");
  slices[1].orientation = { 1, 0, 0, 0.6, 0.8, 0 };
  EXPECT_EQ(refusal(slices),
    "slice 's1': its Image Orientation (Patient) (0020,0037) is not two unit vectors at right "
    "angles (row length 1.000, column length 1.000, row . column 0.600)");
}

TEST(DicomSeriesGeometry, EachSliceNeedsAPositionASpacingAndAllItsPixels)
{
  std::vector<DicomSliceHeader> slices = stackAt({ 0, 1, 2 });
  slices[0].hasPosition = false;
  EXPECT_EQ(refusal(slices),
    "slice 's0': no Image Position (Patient) (0020,0032); without it the slice cannot be placed");
  slices = stackAt({ 0, 1, 2 });
  slices[2].positionMm[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(refusal(slices),
    "slice 's2': its Image Position (Patient) (0020,0032) is not three finite numbers");
  slices = stackAt({ 0, 1, 2 });
  slices[1].pixelSpacingMm[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(refusal(slices),
    "slice 's1': its Pixel Spacing (0028,0030) is not two finite positive numbers of at most "
    "100 mm");
  slices[1].hasPixelSpacing = false;
  EXPECT_EQ(refusal(slices), "slice 's1': no Pixel Spacing (0028,0030)");
  slices = stackAt({ 0, 1, 2 });
  slices[2].pixelBytes = 100;
  EXPECT_EQ(refusal(slices),
    "slice 's2': the file is truncated: it holds 100 bytes of pixel data where its header "
    "promises 128 (8 x 8 pixels)");
  slices = stackAt({ 0, 1, 2 });
  slices[1].columns = 9;
  EXPECT_EQ(refusal(slices), "the slices differ in size: 's1' is 8 x 9 pixels, 's0' 8 x 8");
  EXPECT_EQ(refusal(stackAt({ 4 })), "the DICOM series has a single slice; a 3-D CT is needed");
}

TEST(DicomSeriesGeometry, ATiltedStackWithAGapIsResampledWhereEachVoxelLiesWhenAsked)
{
  // 16 x 12 pixels of 0.75 mm along the rows and 0.5 mm between them, tilted
  // 20 degrees, climbing straight up z with 3 slices missing between 4 and 10.
  const double a = 20.0 * M_PI / 180.0;
  const std::vector<double> heights{ 0, 2, 4, 10, 12 };
  std::vector<DicomSliceHeader> slices = stackAt(heights);
  tilt(slices, 20.0);
  CTVolume stack;
  stack.dims = { 16, 12, static_cast<int>(heights.size()) };
  // A linear field of the patient frame: interpolation must give it back exactly.
  const auto field = [](const std::array<double, 3>& p)
  { return 0.3 * p[0] + 0.2 * p[1] + 0.5 * p[2]; };
  for (DicomSliceHeader& s : slices)
  {
    s.columns = 16;
    s.rows = 12;
    s.pixelSpacingMm = { 0.5, 0.75 };
    s.pixelBytes = s.expectedPixelBytes = 16 * 12 * 2;
    for (int j = 0; j < 12; ++j)
    {
      for (int i = 0; i < 16; ++i)
      {
        const std::array<double, 3> p{ s.positionMm[0] + 0.75 * i,
          s.positionMm[1] + 0.5 * j * std::cos(a), s.positionMm[2] + 0.5 * j * std::sin(a) };
        stack.intensities.push_back(static_cast<float>(field(p)));
      }
    }
  }
  const DicomSeriesLayout layout =
    checkDicomSeriesGeometry(slices, DicomSeriesTolerances(), IrregularSeries::Resample);
  ASSERT_EQ(layout.irregularities.size(), 2u);
  EXPECT_EQ(
    layout.irregularities[0].rfind("the slices are not stacked along their normal: ", 0), 0u);
  EXPECT_EQ(layout.irregularities[1],
    "the slices are not evenly spaced: 's2' and 's3' are 5.64 mm apart where the series steps "
    "1.88 mm (2 slices are missing)");

  const CTVolume volume = resampleDicomStack(stack, layout, slices[0]);
  EXPECT_EQ(volume.dims, (std::array<int, 3>{ 16, 12, 7 }));
  EXPECT_NEAR(volume.spacingMm[2], 2.0 * std::cos(a), 1e-9);
  int inside = 0;
  for (int m = 0; m < 7; ++m)
  {
    for (int j = 0; j < 12; ++j)
    {
      for (int i = 0; i < 16; ++i)
      {
        const float value = volume.intensities[static_cast<std::size_t>((m * 12 + j) * 16 + i)];
        if (value == -1024.0f)
        {
          // Only beside the shifted slices: the first slice is the grid's.
          EXPECT_GT(m, 0) << i << " " << j;
          continue;
        }
        ++inside;
        const double expected = field(volume.indexToPhysical({ double(i), double(j), double(m) }));
        ASSERT_NEAR(value, expected, 1e-3) << i << " " << j << " " << m;
      }
    }
  }
  EXPECT_GT(inside, 16 * 12 * 7 / 2);

  CTVolume wrong = stack;
  wrong.dims[2] = 4;
  EXPECT_EQ(fixtures::errorMessageOf([&] { resampleDicomStack(wrong, layout, slices[0]); }),
    "resampleDicomStack: the stack does not match the series layout");
}
