#include <vimlop/Imaging/DicomSeriesGeometry.h>

#include <vimlop/Core/Error.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

namespace vimlop
{

namespace
{

using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vec3 cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

Vec3 rowDirection(const DicomSliceHeader& s)
{
  return { s.orientation[0], s.orientation[1], s.orientation[2] };
}

Vec3 columnDirection(const DicomSliceHeader& s)
{
  return { s.orientation[3], s.orientation[4], s.orientation[5] };
}

double angleDeg(const Vec3& a, const Vec3& b)
{
  const double c = std::clamp(dot(a, b) / std::sqrt(dot(a, a) * dot(b, b)), -1.0, 1.0);
  return std::acos(c) * 180.0 / M_PI;
}

[[noreturn]] void refuse(const std::ostringstream& problem)
{
  throw Error(problem.str());
}

std::ostringstream message()
{
  std::ostringstream m;
  m << std::fixed << std::setprecision(2);
  return m;
}

/// The checks of one slice on its own.
void checkSlice(const DicomSliceHeader& s, const DicomSeriesTolerances& tolerances)
{
  auto m = message();
  m << "slice '" << s.file << "': ";
  if (!s.hasPosition || !s.hasOrientation)
  {
    m << "no "
      << (s.hasPosition ? "Image Orientation (Patient) (0020,0037)"
                        : "Image Position (Patient) (0020,0032)")
      << "; without it the slice cannot be placed";
    refuse(m);
  }
  const auto& p = s.positionMm;
  if (!std::all_of(p.begin(), p.end(), [](double v) { return std::isfinite(v); }))
  {
    m << "its Image Position (Patient) (0020,0032) is not three finite numbers";
    refuse(m);
  }
  const Vec3 row = rowDirection(s);
  const Vec3 column = columnDirection(s);
  const double rowLength = std::sqrt(dot(row, row));
  const double columnLength = std::sqrt(dot(column, column));
  const double rowDotColumn = dot(row, column);
  if (!(std::abs(rowLength - 1.0) <= tolerances.orthonormality &&
        std::abs(columnLength - 1.0) <= tolerances.orthonormality &&
        std::abs(rowDotColumn) <= tolerances.orthonormality))
  {
    m << std::setprecision(3)
      << "its Image Orientation (Patient) (0020,0037) is not two unit vectors at right angles "
         "(row length "
      << rowLength << ", column length " << columnLength << ", row . column " << rowDotColumn
      << ")";
    refuse(m);
  }
  const auto& spacing = s.pixelSpacingMm;
  if (!s.hasPixelSpacing ||
    !std::all_of(spacing.begin(), spacing.end(),
      [](double v) { return std::isfinite(v) && v > 0.0 && v <= 100.0; }))
  {
    m << (s.hasPixelSpacing ? "its Pixel Spacing (0028,0030) is not two finite positive numbers "
                              "of at most 100 mm"
                            : "no Pixel Spacing (0028,0030)");
    refuse(m);
  }
  if (s.expectedPixelBytes > 0 && s.pixelBytes < s.expectedPixelBytes)
  {
    m << "the file is truncated: it holds " << s.pixelBytes
      << " bytes of pixel data where its header promises " << s.expectedPixelBytes << " (" << s.rows
      << " x " << s.columns << " pixels)";
    refuse(m);
  }
}

} // namespace

DicomSeriesLayout checkDicomSeriesGeometry(const std::vector<DicomSliceHeader>& slices,
  const DicomSeriesTolerances& tolerances, IrregularSeries irregular)
{
  if (slices.size() < 2)
  {
    throw Error("the DICOM series has a single slice; a 3-D CT is needed");
  }
  for (const DicomSliceHeader& s : slices)
  {
    checkSlice(s, tolerances);
  }
  const DicomSliceHeader& first = slices.front();
  for (const DicomSliceHeader& s : slices)
  {
    auto m = message();
    if (s.rows != first.rows || s.columns != first.columns)
    {
      m << "the slices differ in size: '" << s.file << "' is " << s.rows << " x " << s.columns
        << " pixels, '" << first.file << "' " << first.rows << " x " << first.columns;
      refuse(m);
    }
    const double turn = std::max(angleDeg(rowDirection(s), rowDirection(first)),
      angleDeg(columnDirection(s), columnDirection(first)));
    if (turn > tolerances.orientationDeg)
    {
      m << "the slices do not share one orientation: '" << s.file << "' is turned " << turn
        << " degrees from '" << first.file << "'; one volume needs one orientation";
      refuse(m);
    }
  }

  // Distances along the slice normal order the slices, as every DICOM
  // reader does; what is left of a position after that is its drift in the
  // slice plane.
  const Vec3 normal = cross(rowDirection(first), columnDirection(first));
  std::vector<double> along(slices.size());
  for (std::size_t i = 0; i < slices.size(); ++i)
  {
    along[i] = dot(normal, slices[i].positionMm);
  }
  DicomSeriesLayout layout;
  layout.order.resize(slices.size());
  std::iota(layout.order.begin(), layout.order.end(), std::size_t(0));
  std::stable_sort(layout.order.begin(), layout.order.end(),
    [&](std::size_t a, std::size_t b) { return along[a] < along[b]; });

  std::vector<double> steps;
  for (std::size_t k = 0; k + 1 < layout.order.size(); ++k)
  {
    const std::size_t a = layout.order[k];
    const std::size_t b = layout.order[k + 1];
    steps.push_back(along[b] - along[a]);
    if (steps.back() < tolerances.minimumStepDeviationMm)
    {
      auto m = message();
      m << "slices '" << slices[a].file << "' and '" << slices[b].file
        << "' lie at the same position (" << along[a]
        << " mm along the slice normal); a series holds each slice once";
      refuse(m);
    }
  }

  // Refused, or noted for the resampling: the first tilted slice and the
  // first uneven step tell what is wrong.
  const auto irregularity = [&](const std::ostringstream& problem, const char* consequence)
  {
    if (irregular == IrregularSeries::Refuse)
    {
      throw Error(problem.str() + "; " + consequence +
        ": resample it onto a regular grid (--resample-irregular-series)");
    }
    layout.irregularities.push_back(problem.str());
  };
  const std::size_t base = layout.order.front();
  const double pixelMm = std::min(first.pixelSpacingMm[0], first.pixelSpacingMm[1]);
  layout.alongMm.push_back(0.0);
  layout.besideMm.push_back({ 0.0, 0.0 });
  bool tilted = false;
  for (std::size_t k = 1; k < layout.order.size(); ++k)
  {
    const DicomSliceHeader& s = slices[layout.order[k]];
    const double height = along[layout.order[k]] - along[base];
    Vec3 drift{};
    for (int axis = 0; axis < 3; ++axis)
    {
      const double offset = s.positionMm[axis] - slices[base].positionMm[axis];
      drift[axis] = offset - height * normal[axis];
    }
    layout.alongMm.push_back(height);
    layout.besideMm.push_back(
      { dot(drift, rowDirection(first)), dot(drift, columnDirection(first)) });
    const double driftMm = std::sqrt(dot(drift, drift));
    if (!tilted && driftMm > tolerances.inPlaneDriftPixels * pixelMm)
    {
      tilted = true;
      auto m = message();
      m << "the slices are not stacked along their normal: '" << s.file << "' lies " << driftMm
        << " mm beside the normal through '" << slices[base].file << "', " << height
        << " mm from it (a gantry tilt or shear of " << std::atan2(driftMm, height) * 180.0 / M_PI
        << " degrees)";
      irregularity(m, "a regular volume of it would misplace the anatomy");
    }
  }

  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  layout.sliceStepMm = sorted[sorted.size() / 2];
  const double allowed =
    std::max(tolerances.stepFraction * layout.sliceStepMm, tolerances.minimumStepDeviationMm);
  for (std::size_t k = 0; k < steps.size(); ++k)
  {
    if (std::abs(steps[k] - layout.sliceStepMm) <= allowed)
    {
      continue;
    }
    auto m = message();
    m << "the slices are not evenly spaced: '" << slices[layout.order[k]].file << "' and '"
      << slices[layout.order[k + 1]].file << "' are " << steps[k]
      << " mm apart where the series steps " << layout.sliceStepMm << " mm";
    const double multiple = steps[k] / layout.sliceStepMm;
    const long missing = std::lround(multiple) - 1;
    if (missing >= 1 && std::abs(multiple - std::round(multiple)) * layout.sliceStepMm <= allowed)
    {
      m << " (" << missing << (missing == 1 ? " slice is" : " slices are") << " missing)";
    }
    irregularity(m, "a volume with one spacing would misplace the slices beyond them");
    break;
  }
  return layout;
}

namespace
{

/// Bilinear within one slice (columns x rows, row-major by row); NaN beyond its pixels.
double sampleSlice(const float* slice, int columns, int rows, double x, double y)
{
  if (!(x >= 0.0 && y >= 0.0 && x <= columns - 1 && y <= rows - 1))
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const int x0 = std::min(static_cast<int>(x), columns - 2);
  const int y0 = std::min(static_cast<int>(y), rows - 2);
  const double fx = x - x0;
  const double fy = y - y0;
  const float* p = slice + static_cast<std::size_t>(y0) * columns + x0;
  return (1 - fy) * ((1 - fx) * p[0] + fx * p[1]) +
    fy * ((1 - fx) * p[columns] + fx * p[columns + 1]);
}

} // namespace

CTVolume resampleDicomStack(const CTVolume& stack, const DicomSeriesLayout& layout,
  const DicomSliceHeader& first, float fillHU)
{
  const int columns = stack.dims[0];
  const int rows = stack.dims[1];
  const std::size_t count = layout.alongMm.size();
  if (columns < 2 || rows < 2 || count < 2 || static_cast<std::size_t>(stack.dims[2]) != count ||
    layout.besideMm.size() != count || !(layout.sliceStepMm > 0.0) ||
    stack.intensities.size() != stack.numberOfVoxels())
  {
    throw Error("resampleDicomStack: the stack does not match the series layout");
  }
  // DICOM's Pixel Spacing is between rows, then between columns.
  const double columnStepMm = first.pixelSpacingMm[1];
  const double rowStepMm = first.pixelSpacingMm[0];
  const double heightMm = layout.alongMm.back();
  CTVolume volume;
  volume.dims = { columns, rows, static_cast<int>(std::lround(heightMm / layout.sliceStepMm)) + 1 };
  volume.spacingMm = { columnStepMm, rowStepMm, layout.sliceStepMm };
  volume.originMm = first.positionMm;
  const Vec3 row = rowDirection(first);
  const Vec3 column = columnDirection(first);
  const Vec3 normal = cross(row, column);
  for (int r = 0; r < 3; ++r)
  {
    volume.direction[3 * r + 0] = row[r];
    volume.direction[3 * r + 1] = column[r];
    volume.direction[3 * r + 2] = normal[r];
  }
  volume.intensities.resize(volume.numberOfVoxels());
  const std::size_t sliceVoxels = static_cast<std::size_t>(columns) * rows;
  std::size_t below = 0;
  for (int m = 0; m < volume.dims[2]; ++m)
  {
    const double z = std::min(m * layout.sliceStepMm, heightMm);
    while (below + 2 < count && layout.alongMm[below + 1] <= z)
    {
      ++below;
    }
    const double w = std::clamp(
      (z - layout.alongMm[below]) / (layout.alongMm[below + 1] - layout.alongMm[below]), 0.0, 1.0);
    float* out = volume.intensities.data() + static_cast<std::size_t>(m) * sliceVoxels;
    const float* lower = stack.intensities.data() + below * sliceVoxels;
    const float* upper = lower + sliceVoxels;
    const auto& shiftLower = layout.besideMm[below];
    const auto& shiftUpper = layout.besideMm[below + 1];
    for (int j = 0; j < rows; ++j)
    {
      for (int i = 0; i < columns; ++i)
      {
        // The voxel's point in each slice's own pixel coordinates; a voxel
        // one of its two slices does not cover is filled, not half blended.
        const double a = w < 1.0
          ? sampleSlice(
              lower, columns, rows, i - shiftLower[0] / columnStepMm, j - shiftLower[1] / rowStepMm)
          : 0.0;
        const double b = w > 0.0
          ? sampleSlice(
              upper, columns, rows, i - shiftUpper[0] / columnStepMm, j - shiftUpper[1] / rowStepMm)
          : 0.0;
        const double value = (1 - w) * a + w * b;
        out[static_cast<std::size_t>(j) * columns + i] =
          std::isnan(value) ? fillHU : static_cast<float>(value);
      }
    }
  }
  return volume;
}

} // namespace vimlop
