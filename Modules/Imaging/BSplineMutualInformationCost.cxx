// The cost of the B-spline stage of TemplateRegistration: sparse Mattes
// mutual information and bending energy over the control points.
#include <vimlop/Imaging/BSplineMutualInformationCost.h>

#include <itkBSplineInterpolationWeightFunction.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace vimlop::templatereg
{

namespace
{

/// Bins left empty at each end of the histogram so that the cubic Parzen
/// window of an extreme intensity stays inside it (as in Mattes et al.).
constexpr int kPadding = 2;

/// The cubic B-spline, the Parzen window of the moving intensities.
double cubic(double u)
{
  u = std::abs(u);
  return u < 1.0 ? (4.0 - 6.0 * u * u + 3.0 * u * u * u) / 6.0
                 : (u < 2.0 ? (2.0 - u) * (2.0 - u) * (2.0 - u) / 6.0 : 0.0);
}

/// Derivative of cubic().
double cubicDerivative(double u)
{
  const double a = std::abs(u);
  if (a < 1.0)
  {
    return -2.0 * u + 1.5 * u * a;
  }
  return a < 2.0 ? (u > 0.0 ? -0.5 : 0.5) * (2.0 - a) * (2.0 - a) : 0.0;
}

/// Trilinear interpolation of an image, with the gradient of the interpolant
/// (not a finite difference), so that the cost and its derivative agree.
class LinearSampler
{
public:
  explicit LinearSampler(const Image* image)
    : buffer_(image->GetBufferPointer())
  {
    const auto size = image->GetLargestPossibleRegion().GetSize();
    for (unsigned a = 0; a < 3; ++a)
    {
      dims_[a] = static_cast<long>(size[a]);
      origin_[a] = image->GetOrigin()[a];
    }
    // A physical point y has the continuous index M (y - origin), M =
    // spacing^-1 direction^T; the physical gradient is M^T times the index one.
    for (unsigned r = 0; r < 3; ++r)
    {
      for (unsigned c = 0; c < 3; ++c)
      {
        toIndex_[r][c] = image->GetDirection()[c][r] / image->GetSpacing()[r];
      }
    }
  }

  /// Value and physical gradient at `y` (mm); false outside the buffer.
  bool sample(const double y[3], double& value, double gradient[3]) const
  {
    double c[3];
    long i[3];
    double f[3];
    for (unsigned r = 0; r < 3; ++r)
    {
      c[r] = toIndex_[r][0] * (y[0] - origin_[0]) + toIndex_[r][1] * (y[1] - origin_[1]) +
        toIndex_[r][2] * (y[2] - origin_[2]);
      if (!(c[r] >= 0.0 && c[r] <= dims_[r] - 1))
      {
        return false;
      }
      i[r] = std::min(static_cast<long>(c[r]), dims_[r] - 2);
      f[r] = c[r] - i[r];
    }
    const float* p = buffer_ + i[0] + dims_[0] * (i[1] + dims_[1] * i[2]);
    const long sy = dims_[0];
    const long sz = dims_[0] * dims_[1];
    const double v000 = p[0], v100 = p[1], v010 = p[sy], v110 = p[sy + 1];
    const double v001 = p[sz], v101 = p[sz + 1], v011 = p[sz + sy], v111 = p[sz + sy + 1];
    const double x00 = v000 + f[0] * (v100 - v000), x10 = v010 + f[0] * (v110 - v010);
    const double x01 = v001 + f[0] * (v101 - v001), x11 = v011 + f[0] * (v111 - v011);
    const double y0 = x00 + f[1] * (x10 - x00), y1 = x01 + f[1] * (x11 - x01);
    value = y0 + f[2] * (y1 - y0);
    double g[3];
    g[0] = (1 - f[2]) * ((1 - f[1]) * (v100 - v000) + f[1] * (v110 - v010)) +
      f[2] * ((1 - f[1]) * (v101 - v001) + f[1] * (v111 - v011));
    g[1] = (1 - f[2]) * (x10 - x00) + f[2] * (x11 - x01);
    g[2] = y1 - y0;
    for (unsigned a = 0; a < 3; ++a)
    {
      gradient[a] = toIndex_[0][a] * g[0] + toIndex_[1][a] * g[1] + toIndex_[2][a] * g[2];
    }
    return true;
  }

private:
  const float* buffer_;
  long dims_[3];
  double origin_[3];
  double toIndex_[3][3];
};

} // namespace

std::vector<BSplineSample> drawBSplineSamples(
  const Image* fixed, const itk::ImageBase<3>* grid, std::size_t count, unsigned seed)
{
  const auto gridSize = grid->GetLargestPossibleRegion().GetSize();
  const auto size = fixed->GetLargestPossibleRegion().GetSize();
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> along(0.0, 1.0);
  const LinearSampler sampler(fixed);
  auto weightsFunction = itk::BSplineInterpolationWeightFunction<double, 3, 3>::New();
  itk::BSplineInterpolationWeightFunction<double, 3, 3>::WeightsType weights(kBSplineSupport);
  std::vector<BSplineSample> samples;
  samples.reserve(count);
  for (std::size_t n = 0; n < count; ++n)
  {
    itk::ContinuousIndex<double, 3> index;
    for (unsigned a = 0; a < 3; ++a)
    {
      index[a] = along(random) * double(size[a] - 1);
    }
    BSplineSample sample;
    Point x;
    fixed->TransformContinuousIndexToPhysicalPoint(index, x);
    double gradient[3];
    if (!sampler.sample(x.GetDataPointer(), sample.fixedValue, gradient))
    {
      continue;
    }
    itk::ContinuousIndex<double, 3> gridIndex;
    grid->TransformPhysicalPointToContinuousIndex(x, gridIndex);
    itk::Index<3> first;
    weightsFunction->Evaluate(gridIndex, weights, first);
    bool inside = true;
    for (unsigned a = 0; a < 3; ++a)
    {
      sample.xMm[a] = x[a];
      inside = inside && first[a] >= 0 && first[a] + 4 <= static_cast<long>(gridSize[a]);
    }
    if (!inside)
    {
      continue;
    }
    sample.firstNode = first[0] +
      static_cast<long>(gridSize[0]) * (first[1] + static_cast<long>(gridSize[1]) * first[2]);
    for (int k = 0; k < kBSplineSupport; ++k)
    {
      sample.weights[k] = static_cast<float>(weights[static_cast<unsigned>(k)]);
    }
    samples.push_back(sample);
  }
  return samples;
}

BSplineMutualInformationCost::BSplineMutualInformationCost(std::vector<BSplineSample> samples,
  const Image* moving, const double affine[3][4], const BSplineGrid& grid, int bins,
  double bendingWeightMm2)
  : vnl_cost_function(static_cast<int>(3 * grid.nodes()))
  , samples_(std::move(samples))
  , moving_(moving)
  , grid_(grid)
  , bins_(bins)
  , bendingWeightMm2_(bendingWeightMm2)
{
  std::copy(&affine[0][0], &affine[0][0] + 12, &affine_[0][0]);
  double fixedMin = samples_.empty() ? 0.0 : samples_[0].fixedValue;
  double fixedMax = fixedMin;
  for (const BSplineSample& s : samples_)
  {
    fixedMin = std::min(fixedMin, s.fixedValue);
    fixedMax = std::max(fixedMax, s.fixedValue);
  }
  const float* buffer = moving->GetBufferPointer();
  const auto [low, high] =
    std::minmax_element(buffer, buffer + moving->GetLargestPossibleRegion().GetNumberOfPixels());
  // The intensity range spans the bins inside the padding.
  fixedMin_ = fixedMin;
  fixedBin_ = std::max(1e-6, (fixedMax - fixedMin) / (bins_ - 2 * kPadding - 1));
  movingMin_ = *low;
  movingBin_ = std::max(1e-6, (double(*high) - *low) / (bins_ - 2 * kPadding - 1));
  sampleBin_.resize(samples_.size());
  movingPosition_.resize(samples_.size());
  movingGradient_.resize(3 * samples_.size());
}

/// Calls f(k, node) for the 64 support nodes of `sample`, k in the weights' order.
template <class F>
void BSplineMutualInformationCost::forEachNode(const BSplineSample& sample, F&& f) const
{
  const long rowStride = grid_.size[0];
  const long sliceStride = grid_.size[0] * grid_.size[1];
  int k = 0;
  for (long dz = 0; dz < 4; ++dz)
  {
    for (long dy = 0; dy < 4; ++dy)
    {
      const long row = sample.firstNode + dz * sliceStride + dy * rowStride;
      for (long dx = 0; dx < 4; ++dx, ++k)
      {
        f(k, row + dx);
      }
    }
  }
}

/// Runs f(chunk, first, last) over kChunks contiguous ranges of the samples
/// on the pool; each chunk accumulates into its own buffers, summed in chunk
/// order, so the result depends neither on the scheduling nor on the number
/// of threads.
template <class F>
void BSplineMutualInformationCost::parallel(F&& f)
{
  const long n = static_cast<long>(samples_.size());
  pool_.run(static_cast<int>(kChunks),
    [&](int chunk)
    {
      const long c = chunk;
      f(c, n * c / kChunks, n * (c + 1) / kChunks);
    });
}

void BSplineMutualInformationCost::compute(
  const vnl_vector<double>& c, double* value, vnl_vector<double>* gradient)
{
  const std::size_t cells = static_cast<std::size_t>(bins_) * bins_;
  const long nodes = grid_.nodes();
  std::vector<std::vector<double>> histograms(
    static_cast<std::size_t>(kChunks), std::vector<double>(cells, 0.0));
  const LinearSampler sampler(moving_);

  // Pass 1: the moving intensity at each sample, and the joint histogram.
  parallel(
    [&](long chunk, long first, long last)
    {
      std::vector<double>& histogram = histograms[static_cast<std::size_t>(chunk)];
      for (long s = first; s < last; ++s)
      {
        const std::size_t at = static_cast<std::size_t>(s);
        const BSplineSample& sample = samples_[at];
        double b[3] = { sample.xMm[0], sample.xMm[1], sample.xMm[2] };
        forEachNode(sample,
          [&](int k, long node)
          {
            for (long d = 0; d < 3; ++d)
            {
              b[d] += sample.weights[k] * c[static_cast<unsigned>(node + d * nodes)];
            }
          });
        double y[3];
        for (unsigned r = 0; r < 3; ++r)
        {
          y[r] = affine_[r][0] * b[0] + affine_[r][1] * b[1] + affine_[r][2] * b[2] + affine_[r][3];
        }
        double m = 0.0;
        double g[3];
        if (!sampler.sample(y, m, g))
        {
          sampleBin_[at] = -1;
          continue;
        }
        const int i =
          std::clamp(static_cast<int>((sample.fixedValue - fixedMin_) / fixedBin_) + kPadding,
            kPadding, bins_ - kPadding - 1);
        const double eta = std::clamp(
          (m - movingMin_) / movingBin_ + kPadding, double(kPadding), double(bins_ - kPadding - 1));
        sampleBin_[at] = i;
        movingPosition_[at] = eta;
        // The derivative of the moving intensity in b: affine^T times its gradient.
        for (unsigned a = 0; a < 3; ++a)
        {
          movingGradient_[3 * at + a] =
            affine_[0][a] * g[0] + affine_[1][a] * g[1] + affine_[2][a] * g[2];
        }
        const int j0 = static_cast<int>(eta) - 1;
        for (int j = j0; j < j0 + 4; ++j)
        {
          histogram[static_cast<std::size_t>(i) * bins_ + j] += cubic(j - eta);
        }
      }
    });
  std::vector<double>& joint = histograms[0];
  for (std::size_t chunk = 1; chunk < histograms.size(); ++chunk)
  {
    for (std::size_t cell = 0; cell < cells; ++cell)
    {
      joint[cell] += histograms[chunk][cell];
    }
  }
  double total = 0.0;
  for (double h : joint)
  {
    total += h;
  }
  // As ITK's Mattes metric, refuse to go on with too few samples: the
  // transform has left the moving image.
  if (total < 0.05 * static_cast<double>(samples_.size()) || total <= 0.0)
  {
    itkGenericExceptionMacro(<< "too many samples map outside the moving image");
  }
  std::vector<double> fixedMarginal(static_cast<std::size_t>(bins_), 0.0);
  std::vector<double> movingMarginal(static_cast<std::size_t>(bins_), 0.0);
  for (std::size_t i = 0; i < static_cast<std::size_t>(bins_); ++i)
  {
    for (std::size_t j = 0; j < static_cast<std::size_t>(bins_); ++j)
    {
      double& p = joint[i * bins_ + j];
      p /= total;
      fixedMarginal[i] += p;
      movingMarginal[j] += p;
    }
  }
  // logRatio(i, j) = log(p_ij / p_j), the weight of dp_ij in d MI.
  std::vector<double> logRatio(cells, 0.0);
  double information = 0.0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(bins_); ++i)
  {
    for (std::size_t j = 0; j < static_cast<std::size_t>(bins_); ++j)
    {
      const double p = joint[i * bins_ + j];
      if (p > 1e-16)
      {
        logRatio[i * bins_ + j] = std::log(p / movingMarginal[j]);
        information += p * std::log(p / (fixedMarginal[i] * movingMarginal[j]));
      }
    }
  }
  if (gradient)
  {
    gradient->set_size(static_cast<unsigned>(get_number_of_unknowns()));
    gradient->fill(0.0);
  }
  const double bending =
    bendingWeightMm2_ > 0.0 ? bendingEnergy(c, bendingWeightMm2_, gradient) : 0.0;
  if (value)
  {
    *value = -information + bendingWeightMm2_ * bending;
  }
  if (!gradient)
  {
    return;
  }

  // Pass 2: d(-MI)/dc = sum_s a_s d(eta_s)/dc, with a_s = sum_j B3'(j -
  // eta_s) logRatio(i_s, j) / total and d(eta_s)/dc_kd = w_k h_d / bin width.
  const std::size_t parameters = static_cast<std::size_t>(get_number_of_unknowns());
  std::vector<std::vector<double>> partial(
    static_cast<std::size_t>(kChunks), std::vector<double>(parameters, 0.0));
  parallel(
    [&](long chunk, long first, long last)
    {
      std::vector<double>& derivative = partial[static_cast<std::size_t>(chunk)];
      for (long s = first; s < last; ++s)
      {
        const std::size_t at = static_cast<std::size_t>(s);
        const int i = sampleBin_[at];
        if (i < 0)
        {
          continue;
        }
        const double eta = movingPosition_[at];
        const int j0 = static_cast<int>(eta) - 1;
        double a = 0.0;
        for (int j = j0; j < j0 + 4; ++j)
        {
          a += cubicDerivative(j - eta) * logRatio[static_cast<std::size_t>(i) * bins_ + j];
        }
        a /= total * movingBin_;
        const double* h = &movingGradient_[3 * at];
        const BSplineSample& sample = samples_[at];
        forEachNode(sample,
          [&](int k, long node)
          {
            const double w = a * sample.weights[k];
            for (long d = 0; d < 3; ++d)
            {
              derivative[static_cast<std::size_t>(node + d * nodes)] += w * h[d];
            }
          });
      }
    });
  for (std::size_t p = 0; p < parameters; ++p)
  {
    double sum = (*gradient)[static_cast<unsigned>(p)];
    for (const std::vector<double>& d : partial)
    {
      sum += d[p];
    }
    (*gradient)[static_cast<unsigned>(p)] = sum;
  }
}

double BSplineMutualInformationCost::bendingEnergy(
  const vnl_vector<double>& c, double weight, vnl_vector<double>* gradient) const
{
  // The six second differences of each displacement component at a node:
  // d2/dx_a^2 (weight 1) and d2/dx_a dx_b, a < b (weight 2: the Hessian is
  // symmetric).
  struct Term
  {
    long offsets[4];
    double coefficients[4];
    int count;
    double weight;
  };
  const long stride[3] = { 1, grid_.size[0], grid_.size[0] * grid_.size[1] };
  std::vector<Term> terms;
  for (int a = 0; a < 3; ++a)
  {
    const double h2 = grid_.spacingMm[a] * grid_.spacingMm[a];
    terms.push_back({ { -stride[a], 0, stride[a], 0 }, { 1 / h2, -2 / h2, 1 / h2, 0 }, 3, 1.0 });
    for (int b = a + 1; b < 3; ++b)
    {
      const double hh = 4.0 * grid_.spacingMm[a] * grid_.spacingMm[b];
      terms.push_back({ { stride[a] + stride[b], stride[a] - stride[b], -stride[a] + stride[b],
                          -stride[a] - stride[b] },
        { 1 / hh, -1 / hh, -1 / hh, 1 / hh }, 4, 2.0 });
    }
  }
  const long inner = (grid_.size[0] - 2) * (grid_.size[1] - 2) * (grid_.size[2] - 2);
  if (inner <= 0)
  {
    return 0.0;
  }
  const long nodes = grid_.nodes();
  double energy = 0.0;
  for (long z = 1; z + 1 < grid_.size[2]; ++z)
  {
    for (long y = 1; y + 1 < grid_.size[1]; ++y)
    {
      for (long x = 1; x + 1 < grid_.size[0]; ++x)
      {
        for (long d = 0; d < 3; ++d)
        {
          const long base = x * stride[0] + y * stride[1] + z * stride[2] + d * nodes;
          for (const Term& t : terms)
          {
            double v = 0.0;
            for (int m = 0; m < t.count; ++m)
            {
              v += t.coefficients[m] * c[static_cast<unsigned>(base + t.offsets[m])];
            }
            energy += t.weight * v * v;
            if (gradient)
            {
              for (int m = 0; m < t.count; ++m)
              {
                (*gradient)[static_cast<unsigned>(base + t.offsets[m])] +=
                  weight * 2.0 * t.weight * v * t.coefficients[m] / double(inner);
              }
            }
          }
        }
      }
    }
  }
  return energy / double(inner);
}

} // namespace vimlop::templatereg
