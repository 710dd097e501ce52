#include <vimlop/Evaluation/SyntheticDeformation.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TaskPool.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace vimlop
{

namespace
{

/// Uniform in [0, 1) from the generator's raw 32-bit output (portable, unlike
/// the standard distributions, whose algorithms the library chooses).
double uniform01(std::mt19937& generator)
{
  return static_cast<double>(generator()) / 4294967296.0;
}

/// Cubic B-spline weights of the four control points around fraction f in [0, 1).
std::array<double, 4> bsplineWeights(double f)
{
  const double f2 = f * f;
  const double f3 = f2 * f;
  return { (1.0 - f) * (1.0 - f) * (1.0 - f) / 6.0, (3.0 * f3 - 6.0 * f2 + 4.0) / 6.0,
    (-3.0 * f3 + 3.0 * f2 + 3.0 * f + 1.0) / 6.0, f3 / 6.0 };
}

} // namespace

double sampleTrilinear(const CTVolume& volume, const std::array<double, 3>& index)
{
  const std::array<int, 3> d = volume.dims;
  std::array<int, 3> base{};
  std::array<double, 3> f{};
  for (int a = 0; a < 3; ++a)
  {
    if (index[a] < 0.0 || index[a] > d[a] - 1)
    {
      return -1000.0;
    }
    base[a] = std::min(static_cast<int>(index[a]), d[a] - 2);
    f[a] = index[a] - base[a];
  }
  double value = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    double w = 1.0;
    std::size_t at = 0;
    std::size_t stride = 1;
    for (int a = 0; a < 3; ++a)
    {
      const int step = (corner >> a) & 1;
      w *= step ? f[a] : 1.0 - f[a];
      at += stride * static_cast<std::size_t>(base[a] + step);
      stride *= static_cast<std::size_t>(d[a]);
    }
    value += w * volume.intensities[at];
  }
  return value;
}

CTVolume gridOf(const CTVolume& volume)
{
  CTVolume grid;
  grid.dims = volume.dims;
  grid.spacingMm = volume.spacingMm;
  grid.originMm = volume.originMm;
  grid.direction = volume.direction;
  return grid;
}

void addGaussianNoise(CTVolume& volume, double noiseHU, std::uint32_t seed)
{
  if (!(noiseHU > 0.0))
  {
    return;
  }
  std::mt19937 generator(seed);
  for (std::size_t n = 0; n < volume.intensities.size(); n += 2)
  {
    // Box-Muller: two independent normal values per pair of uniforms.
    const double u1 = 1.0 - uniform01(generator);
    const double u2 = uniform01(generator);
    const double radius = noiseHU * std::sqrt(-2.0 * std::log(u1));
    volume.intensities[n] += static_cast<float>(radius * std::cos(2.0 * M_PI * u2));
    if (n + 1 < volume.intensities.size())
    {
      volume.intensities[n + 1] += static_cast<float>(radius * std::sin(2.0 * M_PI * u2));
    }
  }
}

SyntheticDeformation::SyntheticDeformation(
  const CTVolume& grid, const SyntheticDeformationOptions& options)
{
  if (grid.dims[0] < 2 || grid.dims[1] < 2 || grid.dims[2] < 2)
  {
    throw Error("the CT to deform is not a 3-D volume");
  }
  if (!(options.maxDisplacementMm >= 0.0) || !std::isfinite(options.maxDisplacementMm))
  {
    throw Error("the maximum displacement must be a non-negative number of mm");
  }
  this->Grid = gridOf(grid);
  for (int a = 0; a < 3; ++a)
  {
    this->ControlStepVoxels[a] =
      static_cast<int>(std::lround(options.controlSpacingMm / grid.spacingMm[a]));
    if (this->ControlStepVoxels[a] < 2)
    {
      throw Error("the control point spacing must be at least two voxels");
    }
    // Control points from one step before the first voxel to two after the last.
    this->ControlDims[a] = (grid.dims[a] - 1) / this->ControlStepVoxels[a] + 4;
  }
  std::mt19937 generator(options.seed);
  this->Control.resize(3 * static_cast<std::size_t>(this->ControlDims[0]) * this->ControlDims[1] *
    this->ControlDims[2]);
  for (double& c : this->Control)
  {
    c = 2.0 * uniform01(generator) - 1.0;
  }

  // Scale to the requested largest displacement over the region's voxels.
  std::array<int, 3> lo{ 0, 0, 0 };
  std::array<int, 3> hi{ grid.dims[0] - 1, grid.dims[1] - 1, grid.dims[2] - 1 };
  const std::array<double, 6>& r = options.regionMm;
  if (r[0] <= r[1] && r[2] <= r[3] && r[4] <= r[5])
  {
    std::array<double, 3> low{ 1e300, 1e300, 1e300 };
    std::array<double, 3> high{ -1e300, -1e300, -1e300 };
    for (int corner = 0; corner < 8; ++corner)
    {
      const std::array<double, 3> index = grid.physicalToIndex(
        { r[(corner & 1) ? 1 : 0], r[(corner & 2) ? 3 : 2], r[(corner & 4) ? 5 : 4] });
      for (int a = 0; a < 3; ++a)
      {
        low[a] = std::min(low[a], index[a]);
        high[a] = std::max(high[a], index[a]);
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::clamp(static_cast<int>(std::floor(low[a])), 0, grid.dims[a] - 1);
      hi[a] = std::clamp(static_cast<int>(std::ceil(high[a])), 0, grid.dims[a] - 1);
    }
  }
  double largest = 0.0;
  for (int k = lo[2]; k <= hi[2]; ++k)
  {
    for (int j = lo[1]; j <= hi[1]; ++j)
    {
      for (int i = lo[0]; i <= hi[0]; ++i)
      {
        const std::array<double, 3> b =
          this->displacementAtIndex({ double(i), double(j), double(k) });
        largest = std::max(largest, std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));
      }
    }
  }
  const double scale = largest > 0.0 ? options.maxDisplacementMm / largest : 0.0;
  for (double& c : this->Control)
  {
    c *= scale;
  }
  this->Largest = largest * scale;
}

std::array<double, 3> SyntheticDeformation::displacementAtIndex(
  const std::array<double, 3>& index) const
{
  std::array<int, 3> first{};
  std::array<std::array<double, 4>, 3> w{};
  for (int a = 0; a < 3; ++a)
  {
    // Control point m sits at voxel index (m - 1) * step.
    const double u = index[a] / this->ControlStepVoxels[a] + 1.0;
    const double clamped = std::clamp(u, 1.0, static_cast<double>(this->ControlDims[a] - 3));
    int m = static_cast<int>(std::floor(clamped));
    m = std::min(m, this->ControlDims[a] - 3);
    w[a] = bsplineWeights(clamped - m);
    first[a] = m - 1;
  }
  std::array<double, 3> b{ 0.0, 0.0, 0.0 };
  for (int c = 0; c < 4; ++c)
  {
    for (int bb = 0; bb < 4; ++bb)
    {
      const double wkj = w[2][c] * w[1][bb];
      const std::size_t row = static_cast<std::size_t>(this->ControlDims[0]) *
        ((first[1] + bb) + static_cast<std::size_t>(this->ControlDims[1]) * (first[2] + c));
      for (int aa = 0; aa < 4; ++aa)
      {
        const double weight = wkj * w[0][aa];
        const std::size_t at = 3 * (row + static_cast<std::size_t>(first[0] + aa));
        b[0] += weight * this->Control[at];
        b[1] += weight * this->Control[at + 1];
        b[2] += weight * this->Control[at + 2];
      }
    }
  }
  return b;
}

std::array<double, 3> SyntheticDeformation::patientToTemplateDisplacement(
  const std::array<double, 3>& patientPointMm) const
{
  return this->displacementAtIndex(this->Grid.physicalToIndex(patientPointMm));
}

std::array<double, 3> SyntheticDeformation::templateToPatient(const std::array<double, 3>& x) const
{
  std::array<double, 3> y = x;
  for (int iteration = 0; iteration < 200; ++iteration)
  {
    const std::array<double, 3> b = this->patientToTemplateDisplacement(y);
    const std::array<double, 3> next{ x[0] - b[0], x[1] - b[1], x[2] - b[2] };
    const double change = std::hypot(next[0] - y[0], next[1] - y[1], next[2] - y[2]);
    y = next;
    if (change < 1e-7)
    {
      return y;
    }
  }
  throw Error("the synthetic deformation cannot be inverted (too strong for its control spacing)");
}

CTVolume SyntheticDeformation::makePatient(
  const CTVolume& templateCT, double noiseHU, std::uint32_t noiseSeed) const
{
  if (templateCT.dims != this->Grid.dims ||
    templateCT.intensities.size() != templateCT.numberOfVoxels())
  {
    throw Error("the CT to deform does not match the deformation's grid");
  }
  CTVolume patient = templateCT;
  patient.warnings.clear();
  patient.format = "synthetic patient";
  const std::array<int, 3> d = templateCT.dims;
  // Slabs of slices in parallel: each voxel is independent.
  TaskPool().forChunks(d[2], 4,
    [&](int kBegin, int kEnd)
    {
      for (int k = kBegin; k < kEnd; ++k)
      {
        for (int j = 0; j < d[1]; ++j)
        {
          for (int i = 0; i < d[0]; ++i)
          {
            const std::array<double, 3> b =
              this->displacementAtIndex({ double(i), double(j), double(k) });
            const std::array<double, 3> y =
              templateCT.indexToPhysical({ double(i), double(j), double(k) });
            const std::array<double, 3> x{ y[0] + b[0], y[1] + b[1], y[2] + b[2] };
            patient.intensities[static_cast<std::size_t>(i) +
              static_cast<std::size_t>(d[0]) * (j + static_cast<std::size_t>(d[1]) * k)] =
              static_cast<float>(sampleTrilinear(templateCT, templateCT.physicalToIndex(x)));
          }
        }
      }
    });
  // Noise after the (parallel) resampling, in voxel order: reproducible.
  addGaussianNoise(patient, noiseHU, noiseSeed);
  return patient;
}

} // namespace vimlop
