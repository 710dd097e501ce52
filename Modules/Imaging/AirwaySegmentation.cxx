// Airway segmentation with ITK. Like every ITK translation unit this file
// includes no Eigen (Debian's ITK 5.2 carries its own copy under the same
// include guards); it exchanges plain CTVolume data with the rest.
#include <vimlop/Imaging/AirwaySegmentation.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/ITKImageConversion.h>

#include <itkBinaryBallStructuringElement.h>
#include <itkBinaryFillholeImageFilter.h>
#include <itkBinaryMorphologicalClosingImageFilter.h>
#include <itkConnectedComponentImageFilter.h>
#include <itkImageRegionIteratorWithIndex.h>
#include <itkRegionOfInterestImageFilter.h>
#include <itkRelabelComponentImageFilter.h>
#include <itkSignedMaurerDistanceMapImageFilter.h>
#include <itkSliceBySliceImageFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace vimlop
{

namespace
{

using MaskImage = itk::Image<unsigned char, 3>;
using LabelImage = itk::Image<unsigned int, 3>;
using DistanceImage = itk::Image<float, 3>;

std::string formatHU(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.0f HU", value);
  return text;
}

std::string formatPoint(const std::array<double, 3>& p)
{
  char text[96];
  std::snprintf(text, sizeof(text), "(%.1f, %.1f, %.1f) mm", p[0], p[1], p[2]);
  return text;
}

void checkVolume(const CTVolume& ct)
{
  for (int axis = 0; axis < 3; ++axis)
  {
    if (ct.dims[axis] < 2)
    {
      std::ostringstream msg;
      msg << "the CT is " << ct.dims[0] << " x " << ct.dims[1] << " x " << ct.dims[2]
          << " voxels: a 3-D volume is needed";
      throw Error(msg.str());
    }
    if (!(ct.spacingMm[axis] > 0.0) || !std::isfinite(ct.spacingMm[axis]))
    {
      throw Error("the CT has a non-positive or non-finite voxel spacing");
    }
  }
  if (ct.intensities.size() != ct.numberOfVoxels())
  {
    throw Error("the CT's intensities do not match its dimensions");
  }
}

/// Index axis closest to the patient's superior direction (LPS z): the axial slices are across it.
unsigned axialAxis(const CTVolume& ct)
{
  unsigned best = 2;
  double largest = -1.0;
  for (unsigned axis = 0; axis < 3; ++axis)
  {
    const double z = std::abs(ct.direction[6 + axis]);
    if (z > largest)
    {
      largest = z;
      best = axis;
    }
  }
  return best;
}

/// Components of a mask, relabelled 1, 2, ... by decreasing size (voxels).
struct Components
{
  LabelImage::Pointer labels;
  std::vector<itk::SizeValueType> sizes;
};

Components components(const MaskImage* mask, bool fullyConnected)
{
  auto connected = itk::ConnectedComponentImageFilter<MaskImage, LabelImage>::New();
  connected->SetInput(mask);
  connected->SetFullyConnected(fullyConnected);
  auto relabel = itk::RelabelComponentImageFilter<LabelImage, LabelImage>::New();
  relabel->SetInput(connected->GetOutput());
  relabel->SetSortByObjectSize(true);
  relabel->Update();
  return { relabel->GetOutput(), relabel->GetSizeOfObjectsInPixels() };
}

/// Ball radius in voxels, per axis, for a radius in mm.
MaskImage::SizeType radiusInVoxels(const CTVolume& ct, double radiusMm)
{
  MaskImage::SizeType radius;
  for (unsigned axis = 0; axis < 3; ++axis)
  {
    radius[axis] = static_cast<itk::SizeValueType>(std::floor(radiusMm / ct.spacingMm[axis]));
  }
  return radius;
}

/// Bounds (x min, x max, y min, ...) of the physical centres of the voxels where `inside(i)`.
template <typename Predicate>
std::array<double, 6> physicalBounds(const CTVolume& grid, Predicate inside)
{
  std::array<int, 6> box{ grid.dims[0], -1, grid.dims[1], -1, grid.dims[2], -1 };
  std::size_t i = 0;
  for (int k = 0; k < grid.dims[2]; ++k)
  {
    for (int j = 0; j < grid.dims[1]; ++j)
    {
      for (int x = 0; x < grid.dims[0]; ++x, ++i)
      {
        if (inside(i))
        {
          box[0] = std::min(box[0], x);
          box[1] = std::max(box[1], x);
          box[2] = std::min(box[2], j);
          box[3] = std::max(box[3], j);
          box[4] = std::min(box[4], k);
          box[5] = std::max(box[5], k);
        }
      }
    }
  }
  std::array<double, 6> bounds{ std::numeric_limits<double>::max(),
    -std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
    -std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
    -std::numeric_limits<double>::max() };
  for (int corner = 0; corner < 8; ++corner)
  {
    const std::array<double, 3> index{ static_cast<double>(box[(corner & 1) ? 1 : 0]),
      static_cast<double>(box[(corner & 2) ? 3 : 2]),
      static_cast<double>(box[(corner & 4) ? 5 : 4]) };
    const std::array<double, 3> p = grid.indexToPhysical(index);
    for (int axis = 0; axis < 3; ++axis)
    {
      bounds[2 * axis] = std::min(bounds[2 * axis], p[axis]);
      bounds[2 * axis + 1] = std::max(bounds[2 * axis + 1], p[axis]);
    }
  }
  return bounds;
}

/// The voxel index nearest to a physical point, or nothing if the point is outside the volume.
std::optional<std::array<int, 3>> nearestVoxel(const CTVolume& ct, const std::array<double, 3>& p)
{
  // index = diag(1/spacing) D^T (p - origin): the direction matrix is orthonormal.
  std::array<int, 3> index{};
  for (int axis = 0; axis < 3; ++axis)
  {
    double projection = 0.0;
    for (int row = 0; row < 3; ++row)
    {
      projection += ct.direction[3 * row + axis] * (p[row] - ct.originMm[row]);
    }
    const double continuous = projection / ct.spacingMm[axis];
    if (!std::isfinite(continuous) || continuous < -0.5 || continuous > ct.dims[axis] - 0.5)
    {
      return std::nullopt;
    }
    index[axis] = std::clamp(static_cast<int>(std::lround(continuous)), 0, ct.dims[axis] - 1);
  }
  return index;
}

} // namespace

AirwaySegmentation AirwaySegmentation::compute(
  const CTVolume& ct, const AirwaySegmentationOptions& options, const ProgressCallback& progress)
{
  checkVolume(ct);
  const std::size_t n = ct.numberOfVoxels();
  const double voxelMm3 = ct.spacingMm[0] * ct.spacingMm[1] * ct.spacingMm[2];
  reportProgress(progress, 0.0, "thresholds");

  // Thresholds that cannot separate anything are the user's to fix: say so
  // before any work, with the intensity range to choose from.
  const auto [lowest, highest] = std::minmax_element(ct.intensities.begin(), ct.intensities.end());
  const std::string range =
    "(intensities span " + formatHU(*lowest) + " .. " + formatHU(*highest) + ")";
  if (!(*lowest < options.airThresholdHU))
  {
    throw Error(
      "the air threshold " + formatHU(options.airThresholdHU) + " selects no voxel " + range);
  }
  if (*highest < options.airThresholdHU)
  {
    throw Error(
      "the air threshold " + formatHU(options.airThresholdHU) + " selects every voxel " + range);
  }
  if (!(*highest > options.bodyThresholdHU))
  {
    throw Error(
      "no tissue above " + formatHU(options.bodyThresholdHU) + ": there is no head " + range);
  }

  // 1. Head mask.
  MaskImage::Pointer tissue = itkconv::allocateLike<MaskImage>(ct);
  {
    unsigned char* t = tissue->GetBufferPointer();
    for (std::size_t i = 0; i < n; ++i)
    {
      t[i] = ct.intensities[i] > options.bodyThresholdHU ? 1 : 0;
    }
  }
  reportProgress(progress, 0.05, "head mask");
  Components tissueParts = components(tissue, false);
  {
    // Keep the largest tissue component only.
    const unsigned int* l = tissueParts.labels->GetBufferPointer();
    unsigned char* t = tissue->GetBufferPointer();
    for (std::size_t i = 0; i < n; ++i)
    {
      t[i] = l[i] == 1 ? 1 : 0;
    }
    tissueParts.labels = nullptr;
  }
  MaskImage::Pointer head = tissue;
  if (options.bodyClosingRadiusMm > 0.0)
  {
    reportProgress(progress, 0.2, "closing the head mask");
    using Ball = itk::BinaryBallStructuringElement<unsigned char, 3>;
    Ball ball;
    ball.SetRadius(radiusInVoxels(ct, options.bodyClosingRadiusMm));
    ball.CreateStructuringElement();
    auto closing = itk::BinaryMorphologicalClosingImageFilter<MaskImage, MaskImage, Ball>::New();
    closing->SetInput(tissue);
    closing->SetKernel(ball);
    closing->SetForegroundValue(1);
    closing->SetSafeBorder(true);
    closing->Update();
    head = closing->GetOutput();
  }
  reportProgress(progress, 0.4, "filling the head slice by slice");
  {
    using Slice = itk::Image<unsigned char, 2>;
    auto fill = itk::BinaryFillholeImageFilter<Slice>::New();
    fill->SetForegroundValue(1);
    // Fully connected foreground, so background holes are face-connected:
    // a diagonal gap in a slice does not let the outside in.
    fill->SetFullyConnected(true);
    auto slices = itk::SliceBySliceImageFilter<MaskImage, MaskImage>::New();
    slices->SetInput(head);
    slices->SetFilter(fill);
    slices->SetDimension(axialAxis(ct));
    slices->Update();
    head = slices->GetOutput();
  }
  AirwaySegmentation result;
  result.label = ct;
  result.label.format = "airway label";
  result.label.warnings.clear();
  const unsigned char* h = head->GetBufferPointer();
  result.headBoundsMm = physicalBounds(ct, [h](std::size_t i) { return h[i] != 0; });

  // 2. Interior air.
  reportProgress(progress, 0.55, "interior air");
  MaskImage::Pointer air = itkconv::allocateLike<MaskImage>(ct);
  std::size_t airVoxels = 0;
  {
    unsigned char* a = air->GetBufferPointer();
    for (std::size_t i = 0; i < n; ++i)
    {
      a[i] = (h[i] != 0 && ct.intensities[i] < options.airThresholdHU) ? 1 : 0;
      airVoxels += a[i];
    }
  }
  if (airVoxels == 0)
  {
    throw Error("no air inside the head: no voxel below " + formatHU(options.airThresholdHU) +
      " is enclosed by tissue above " + formatHU(options.bodyThresholdHU));
  }
  head = nullptr;
  tissue = nullptr;
  // Face connectivity: cavities that touch only along a voxel edge stay apart.
  Components airParts = components(air, false);
  const unsigned int* labels = airParts.labels->GetBufferPointer();
  result.interiorAirComponents = static_cast<int>(airParts.sizes.size());

  // 3. Choice.
  reportProgress(progress, 0.7, "choosing the airway");
  unsigned int chosen = 1;
  if (options.seedMm)
  {
    const std::array<double, 3>& seed = *options.seedMm;
    const std::optional<std::array<int, 3>> index = nearestVoxel(ct, seed);
    if (!index)
    {
      throw Error("the seed point " + formatPoint(seed) + " is outside the CT volume");
    }
    const std::size_t at = static_cast<std::size_t>((*index)[0]) +
      static_cast<std::size_t>(ct.dims[0]) *
        ((*index)[1] + static_cast<std::size_t>(ct.dims[1]) * (*index)[2]);
    chosen = labels[at];
    if (chosen == 0)
    {
      const bool isAir = ct.intensities[at] < options.airThresholdHU;
      throw Error("the seed point " + formatPoint(seed) + " is " +
        (isAir ? "in air outside the head" : "in tissue") + " (" + formatHU(ct.intensities[at]) +
        "), not in air inside the head");
    }
    result.selection = "seed";
  }
  else
  {
    result.selection = "largest";
  }
  const double chosenVolume = static_cast<double>(airParts.sizes[chosen - 1]) * voxelMm3;
  if (chosenVolume < options.minimumVolumeMm3)
  {
    char text[64];
    std::snprintf(text, sizeof(text), "%.0f mm^3 (at least %.0f mm^3 needed)", chosenVolume,
      options.minimumVolumeMm3);
    throw Error(std::string("no airway inside the head: the ") +
      (options.seedMm ? "seeded" : "largest") + " air pocket below " +
      formatHU(options.airThresholdHU) + " is " + text);
  }

  // 4. Sinuses within reach.
  std::vector<bool> included(airParts.sizes.size() + 1, false);
  included[chosen] = true;
  if (options.sinusInclusionDistanceMm > 0.0)
  {
    reportProgress(progress, 0.75, "sinuses");
    MaskImage::Pointer airway = itkconv::allocateLike<MaskImage>(ct);
    unsigned char* w = airway->GetBufferPointer();
    for (std::size_t i = 0; i < n; ++i)
    {
      w[i] = labels[i] == chosen ? 1 : 0;
    }
    auto distance = itk::SignedMaurerDistanceMapImageFilter<MaskImage, DistanceImage>::New();
    distance->SetInput(airway);
    distance->SetUseImageSpacing(true);
    distance->SetSquaredDistance(false);
    distance->SetInsideIsPositive(false);
    distance->SetBackgroundValue(0);
    distance->Update();
    const float* d = distance->GetOutput()->GetBufferPointer();
    for (std::size_t i = 0; i < n; ++i)
    {
      if (labels[i] != 0 && labels[i] != chosen && d[i] <= options.sinusInclusionDistanceMm &&
        !included[labels[i]])
      {
        included[labels[i]] = true;
        ++result.includedSinuses;
        result.includedSinusVolumeMm3 +=
          static_cast<double>(airParts.sizes[labels[i] - 1]) * voxelMm3;
      }
    }
  }
  for (std::size_t c = 1; c < included.size(); ++c)
  {
    if (!included[c])
    {
      result.nextLargestVolumeMm3 = static_cast<double>(airParts.sizes[c - 1]) * voxelMm3;
      break;
    }
  }

  // 5. Clean-up: fill tissue cavities enclosed by the airway.
  reportProgress(progress, 0.85, "clean-up");
  {
    unsigned char* a = air->GetBufferPointer();
    for (std::size_t i = 0; i < n; ++i)
    {
      a[i] = included[labels[i]] ? 1 : 0;
    }
  }
  airParts.labels = nullptr;
  auto fill = itk::BinaryFillholeImageFilter<MaskImage>::New();
  fill->SetInput(air);
  fill->SetForegroundValue(1);
  fill->SetFullyConnected(false);
  fill->Update();
  const unsigned char* airway = fill->GetOutput()->GetBufferPointer();

  std::array<double, 3> sum{ 0.0, 0.0, 0.0 };
  std::size_t i = 0;
  for (int k = 0; k < ct.dims[2]; ++k)
  {
    for (int j = 0; j < ct.dims[1]; ++j)
    {
      for (int x = 0; x < ct.dims[0]; ++x, ++i)
      {
        const bool in = airway[i] != 0;
        result.label.intensities[i] = in ? 1.0f : 0.0f;
        if (in)
        {
          ++result.voxelCount;
          sum[0] += x;
          sum[1] += j;
          sum[2] += k;
        }
      }
    }
  }
  const double count = static_cast<double>(result.voxelCount);
  result.centroidMm = ct.indexToPhysical({ sum[0] / count, sum[1] / count, sum[2] / count });
  result.volumeMm3 = count * voxelMm3;
  result.boundsMm =
    physicalBounds(ct, [&result](std::size_t v) { return result.label.intensities[v] != 0.0f; });
  reportProgress(progress, 1.0, "done");
  return result;
}

std::vector<AirwaySegmentation::InteriorPoint> AirwaySegmentation::deepestPoints(
  int count, double minimumSeparationMm) const
{
  const CTVolume& grid = this->label;
  if (grid.intensities.size() != grid.numberOfVoxels() || this->voxelCount == 0)
  {
    throw Error("the airway label is empty");
  }
  // Work in the airway's bounding box plus a margin of background, so the
  // distance map is small and the border counts as tissue.
  std::array<int, 3> lo{ grid.dims[0], grid.dims[1], grid.dims[2] };
  std::array<int, 3> hi{ -1, -1, -1 };
  std::size_t i = 0;
  for (int k = 0; k < grid.dims[2]; ++k)
  {
    for (int j = 0; j < grid.dims[1]; ++j)
    {
      for (int x = 0; x < grid.dims[0]; ++x, ++i)
      {
        if (grid.intensities[i] != 0.0f)
        {
          const std::array<int, 3> v{ x, j, k };
          for (int a = 0; a < 3; ++a)
          {
            lo[a] = std::min(lo[a], v[a]);
            hi[a] = std::max(hi[a], v[a]);
          }
        }
      }
    }
  }
  CTVolume box;
  for (int a = 0; a < 3; ++a)
  {
    box.dims[a] = hi[a] - lo[a] + 3;
  }
  box.spacingMm = grid.spacingMm;
  box.direction = grid.direction;
  box.originMm = grid.indexToPhysical({ lo[0] - 1.0, lo[1] - 1.0, lo[2] - 1.0 });
  MaskImage::Pointer mask = itkconv::allocateLike<MaskImage>(box);
  mask->FillBuffer(0);
  unsigned char* m = mask->GetBufferPointer();
  for (int k = lo[2]; k <= hi[2]; ++k)
  {
    for (int j = lo[1]; j <= hi[1]; ++j)
    {
      for (int x = lo[0]; x <= hi[0]; ++x)
      {
        const std::size_t from = static_cast<std::size_t>(x) +
          static_cast<std::size_t>(grid.dims[0]) * (j + static_cast<std::size_t>(grid.dims[1]) * k);
        const std::size_t to = static_cast<std::size_t>(x - lo[0] + 1) +
          static_cast<std::size_t>(box.dims[0]) *
            ((j - lo[1] + 1) + static_cast<std::size_t>(box.dims[1]) * (k - lo[2] + 1));
        m[to] = grid.intensities[from] != 0.0f ? 1 : 0;
      }
    }
  }
  auto distance = itk::SignedMaurerDistanceMapImageFilter<MaskImage, DistanceImage>::New();
  distance->SetInput(mask);
  distance->SetUseImageSpacing(true);
  distance->SetSquaredDistance(false);
  distance->SetInsideIsPositive(true);
  distance->SetBackgroundValue(0);
  distance->Update();
  const float* d = distance->GetOutput()->GetBufferPointer();

  // Local maxima over the 26 neighbours (plateaus keep every voxel; the
  // separation below thins them out).
  struct Candidate
  {
    float depth;
    std::array<int, 3> index;
  };
  std::vector<Candidate> candidates;
  const int nx = box.dims[0];
  const int ny = box.dims[1];
  for (int k = 1; k + 1 < box.dims[2]; ++k)
  {
    for (int j = 1; j + 1 < ny; ++j)
    {
      for (int x = 1; x + 1 < nx; ++x)
      {
        const std::size_t at = static_cast<std::size_t>(x) +
          static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k);
        if (m[at] == 0)
        {
          continue;
        }
        bool isMaximum = true;
        for (int dz = -1; dz <= 1 && isMaximum; ++dz)
        {
          for (int dy = -1; dy <= 1 && isMaximum; ++dy)
          {
            for (int dx = -1; dx <= 1 && isMaximum; ++dx)
            {
              const std::size_t other = static_cast<std::size_t>(x + dx) +
                static_cast<std::size_t>(nx) * ((j + dy) + static_cast<std::size_t>(ny) * (k + dz));
              isMaximum = d[other] <= d[at];
            }
          }
        }
        if (isMaximum)
        {
          candidates.push_back({ d[at], { x, j, k } });
        }
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
    [](const Candidate& a, const Candidate& b) { return a.depth > b.depth; });
  std::vector<InteriorPoint> points;
  for (const Candidate& c : candidates)
  {
    if (static_cast<int>(points.size()) >= count)
    {
      break;
    }
    InteriorPoint point;
    point.pointMm = box.indexToPhysical({ static_cast<double>(c.index[0]),
      static_cast<double>(c.index[1]), static_cast<double>(c.index[2]) });
    point.depthMm = c.depth;
    const bool farEnough = std::all_of(points.begin(), points.end(),
      [&](const InteriorPoint& p)
      {
        double squared = 0.0;
        for (int a = 0; a < 3; ++a)
        {
          squared += (p.pointMm[a] - point.pointMm[a]) * (p.pointMm[a] - point.pointMm[a]);
        }
        return squared >= minimumSeparationMm * minimumSeparationMm;
      });
    if (farEnough)
    {
      points.push_back(point);
    }
  }
  return points;
}

std::string AirwaySegmentation::summaryText() const
{
  return formatText("airway %.1f cm^3 (%s of %d interior air components; next largest %.1f "
                    "cm^3; %d sinuses added), centroid (%.1f, %.1f, %.1f) mm LPS",
    this->volumeMm3 / 1000.0, this->selection == "seed" ? "seeded, one" : "largest",
    this->interiorAirComponents, this->nextLargestVolumeMm3 / 1000.0, this->includedSinuses,
    this->centroidMm[0], this->centroidMm[1], this->centroidMm[2]);
}

} // namespace vimlop
