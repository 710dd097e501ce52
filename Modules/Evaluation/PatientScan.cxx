#include <vimlop/Evaluation/PatientScan.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TaskPool.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/SyntheticDeformation.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace vimlop
{

namespace
{

/// Convolves `volume` along `axis` with a normalised Gaussian of `sigmaVoxels`
/// (edges clamped).
void blurAxis(CTVolume& volume, int axis, double sigmaVoxels)
{
  if (!(sigmaVoxels > 0.05))
  {
    return;
  }
  const int radius = static_cast<int>(std::ceil(3.0 * sigmaVoxels));
  std::vector<double> kernel(static_cast<std::size_t>(2 * radius + 1));
  double sum = 0.0;
  for (int t = -radius; t <= radius; ++t)
  {
    kernel[static_cast<std::size_t>(t + radius)] =
      std::exp(-0.5 * t * t / (sigmaVoxels * sigmaVoxels));
    sum += kernel[static_cast<std::size_t>(t + radius)];
  }
  for (double& k : kernel)
  {
    k /= sum;
  }
  const std::array<int, 3> d = volume.dims;
  const std::size_t stride =
    axis == 0 ? 1 : (axis == 1 ? std::size_t(d[0]) : std::size_t(d[0]) * d[1]);
  const int length = d[axis];
  // The lines along `axis`, numbered by the other two indices.
  const int u = axis == 0 ? 1 : 0;
  const int v = axis == 2 ? 1 : 2;
  // Each line is read into a buffer before it is overwritten.
  TaskPool().forChunks(d[v], 4,
    [&](int first, int last)
    {
      std::vector<float> line(static_cast<std::size_t>(length));
      for (int b = first; b < last; ++b)
      {
        for (int a = 0; a < d[u]; ++a)
        {
          std::array<std::size_t, 3> index{ 0, 0, 0 };
          index[static_cast<std::size_t>(u)] = static_cast<std::size_t>(a);
          index[static_cast<std::size_t>(v)] = static_cast<std::size_t>(b);
          const std::size_t start =
            index[0] + std::size_t(d[0]) * (index[1] + std::size_t(d[1]) * index[2]);
          for (int i = 0; i < length; ++i)
          {
            line[static_cast<std::size_t>(i)] =
              volume.intensities[start + stride * static_cast<std::size_t>(i)];
          }
          for (int i = 0; i < length; ++i)
          {
            double value = 0.0;
            for (int t = -radius; t <= radius; ++t)
            {
              const int at = std::clamp(i + t, 0, length - 1);
              value +=
                kernel[static_cast<std::size_t>(t + radius)] * line[static_cast<std::size_t>(at)];
            }
            volume.intensities[start + stride * static_cast<std::size_t>(i)] =
              static_cast<float>(value);
          }
        }
      }
    });
}

} // namespace

bool PatientScanOptions::isTemplateGrid() const
{
  return pixelSpacingMm == 0.0 && sliceSpacingMm == 0.0 && blurMm == 0.0 && rotationDeg == 0.0 &&
    shiftMm == std::array<double, 3>{ 0.0, 0.0, 0.0 };
}

void PatientScanOptions::validate() const
{
  auto check = [](bool ok, const char* what, double value)
  {
    if (!ok)
    {
      throw Error(formatText("patient scan: %s %g is out of range", what, value));
    }
  };
  check(pixelSpacingMm == 0.0 || (pixelSpacingMm >= 0.1 && pixelSpacingMm <= 5.0),
    "pixel spacing (0 or 0.1-5 mm)", pixelSpacingMm);
  check(sliceSpacingMm == 0.0 || (sliceSpacingMm >= 0.1 && sliceSpacingMm <= 10.0),
    "slice spacing (0 or 0.1-10 mm)", sliceSpacingMm);
  check(blurMm >= 0.0 && blurMm <= 5.0, "blur (0-5 mm)", blurMm);
  check(std::abs(rotationDeg) <= 30.0, "rotation (-30 to 30 deg)", rotationDeg);
  for (double s : shiftMm)
  {
    check(std::abs(s) <= 50.0, "shift (-50 to 50 mm per axis)", s);
  }
}

PatientScan::PatientScan(const CTVolume& templateGrid, const PatientScanOptions& options)
  : Options(options)
{
  options.validate();
  this->Grid = gridOf(templateGrid);
  this->CentreMm = templateGrid.indexToPhysical({ 0.5 * (templateGrid.dims[0] - 1),
    0.5 * (templateGrid.dims[1] - 1), 0.5 * (templateGrid.dims[2] - 1) });
  const double a = options.rotationDeg * M_PI / 180.0;
  this->Rotation = { { { 1.0, 0.0, 0.0 }, { 0.0, std::cos(a), -std::sin(a) },
    { 0.0, std::sin(a), std::cos(a) } } };
}

std::array<double, 3> PatientScan::place(const std::array<double, 3>& x) const
{
  std::array<double, 3> y{};
  for (int r = 0; r < 3; ++r)
  {
    y[r] = this->CentreMm[r] + this->Options.shiftMm[r];
    for (int c = 0; c < 3; ++c)
    {
      y[r] += this->Rotation[r][c] * (x[c] - this->CentreMm[c]);
    }
  }
  return y;
}

CTVolume PatientScan::scan(CTVolume deformed, double noiseHU, std::uint32_t noiseSeed) const
{
  if (deformed.dims != this->Grid.dims || deformed.intensities.size() != deformed.numberOfVoxels())
  {
    throw Error("the head to scan does not match the scan's template grid");
  }
  CTVolume patient = this->Grid;
  patient.format = "synthetic patient";
  const std::array<double, 3> spacing{
    this->Options.pixelSpacingMm > 0.0 ? this->Options.pixelSpacingMm : this->Grid.spacingMm[0],
    this->Options.pixelSpacingMm > 0.0 ? this->Options.pixelSpacingMm : this->Grid.spacingMm[1],
    this->Options.sliceSpacingMm > 0.0 ? this->Options.sliceSpacingMm : this->Grid.spacingMm[2]
  };

  // The blur: a new voxel's profile beyond the old one's, and the kernel's.
  // Blurred in place: `deformed` is this call's own copy.
  for (int a = 0; a < 3; ++a)
  {
    const double profile =
      std::max(0.0, spacing[a] * spacing[a] - this->Grid.spacingMm[a] * this->Grid.spacingMm[a]) /
      (2.355 * 2.355);
    const double sigmaMm = std::sqrt(this->Options.blurMm * this->Options.blurMm + profile);
    blurAxis(deformed, a, sigmaMm / this->Grid.spacingMm[a]);
  }

  // The new grid over the same extent.
  for (int a = 0; a < 3; ++a)
  {
    const double extent = this->Grid.spacingMm[a] * (this->Grid.dims[a] - 1);
    patient.spacingMm[a] = spacing[a];
    patient.dims[a] = static_cast<int>(std::floor(extent / spacing[a] + 1e-9)) + 1;
  }
  patient.intensities.assign(patient.numberOfVoxels(), -1000.0f);
  const std::array<int, 3> d = patient.dims;
  TaskPool().forChunks(d[2], 4,
    [&](int first, int last)
    {
      for (int k = first; k < last; ++k)
      {
        for (int j = 0; j < d[1]; ++j)
        {
          for (int i = 0; i < d[0]; ++i)
          {
            const std::array<double, 3> y =
              patient.indexToPhysical({ double(i), double(j), double(k) });
            // M^-1(y) = R^T (y - c - shift) + c.
            std::array<double, 3> x{};
            for (int c = 0; c < 3; ++c)
            {
              x[c] = this->CentreMm[c];
              for (int r = 0; r < 3; ++r)
              {
                x[c] +=
                  this->Rotation[r][c] * (y[r] - this->CentreMm[r] - this->Options.shiftMm[r]);
              }
            }
            patient.intensities[static_cast<std::size_t>(i) +
              static_cast<std::size_t>(d[0]) * (j + static_cast<std::size_t>(d[1]) * k)] =
              static_cast<float>(sampleTrilinear(deformed, deformed.physicalToIndex(x)));
          }
        }
      }
    });
  addGaussianNoise(patient, noiseHU, noiseSeed);
  return patient;
}

} // namespace vimlop
