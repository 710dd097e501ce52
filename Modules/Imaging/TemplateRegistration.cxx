// Template-to-patient registration with ITK. This is the module's heaviest
// translation unit (ITK's v4 registration templates), so all the ITK work of
// the registration lives here, instantiated for float images only. Like every
// ITK translation unit it includes no Eigen (see CTVolume.h).
#include <vimlop/Imaging/TemplateRegistration.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/ITKImageConversion.h>
#include <vimlop/Imaging/VolumeCrop.h>

#include <itkAffineTransform.h>
#include <itkCommand.h>
#include <itkDisplacementFieldTransform.h>
#include <itkDisplacementFieldTransformParametersAdaptor.h>
#include <itkImageRegistrationMethodv4.h>
#include <itkLinearInterpolateImageFunction.h>
#include <itkMattesMutualInformationImageToImageMetricv4.h>
#include <itkMeanSquaresImageToImageMetricv4.h>
#include <itkRegistrationParameterScalesFromPhysicalShift.h>
#include <itkRegularStepGradientDescentOptimizerv4.h>
#include <itkShrinkImageFilter.h>
#include <itkSyNImageRegistrationMethod.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

namespace vimlop
{

namespace
{

using Image = itk::Image<float, 3>;
using AffineTransform = itk::AffineTransform<double, 3>;
using FieldTransform = itk::DisplacementFieldTransform<double, 3>;
using Point = itk::Point<double, 3>;
using Clock = std::chrono::steady_clock;

constexpr float kLowestHU = -1000.0f;
constexpr float kHighestHU = 2000.0f;
constexpr double kTissueHU = -500.0;

/// Calls a function on an ITK event.
class Observer : public itk::Command
{
public:
  using Pointer = itk::SmartPointer<Observer>;
  static Pointer New()
  {
    Pointer observer = new Observer;
    observer->UnRegister(); // the smart pointer holds the only reference
    return observer;
  }
  void Execute(itk::Object*, const itk::EventObject&) override { this->Callback(); }
  void Execute(const itk::Object*, const itk::EventObject&) override { this->Callback(); }
  std::function<void()> Callback;
};

double seconds(Clock::time_point since)
{
  return std::chrono::duration<double>(Clock::now() - since).count();
}

/// Continuous index of a physical point in a volume (orthonormal direction).
std::array<double, 3> physicalToIndex(const CTVolume& v, const std::array<double, 3>& p)
{
  std::array<double, 3> index{};
  for (int col = 0; col < 3; ++col)
  {
    double projection = 0.0;
    for (int row = 0; row < 3; ++row)
    {
      projection += v.direction[3 * row + col] * (p[row] - v.originMm[row]);
    }
    index[col] = projection / v.spacingMm[col];
  }
  return index;
}

/// Centroid (physical) of the voxels above the tissue threshold; every other voxel is enough.
std::array<double, 3> tissueCentroid(const CTVolume& v)
{
  std::array<double, 3> sum{ 0.0, 0.0, 0.0 };
  double count = 0.0;
  for (int k = 0; k < v.dims[2]; k += 2)
  {
    for (int j = 0; j < v.dims[1]; j += 2)
    {
      for (int i = 0; i < v.dims[0]; i += 2)
      {
        const std::size_t n = static_cast<std::size_t>(i) +
          static_cast<std::size_t>(v.dims[0]) * (j + static_cast<std::size_t>(v.dims[1]) * k);
        if (v.intensities[n] > kTissueHU)
        {
          sum[0] += i;
          sum[1] += j;
          sum[2] += k;
          count += 1.0;
        }
      }
    }
  }
  if (count == 0.0)
  {
    return v.indexToPhysical(
      { 0.5 * (v.dims[0] - 1), 0.5 * (v.dims[1] - 1), 0.5 * (v.dims[2] - 1) });
  }
  return v.indexToPhysical({ sum[0] / count, sum[1] / count, sum[2] / count });
}

/// Integer shrink factors per axis that bring `spacing` closest to `targetMm`.
itk::ShrinkImageFilter<Image, Image>::ShrinkFactorsType shrinkFactors(
  const std::array<double, 3>& spacing, double targetMm)
{
  itk::ShrinkImageFilter<Image, Image>::ShrinkFactorsType factors;
  for (unsigned a = 0; a < 3; ++a)
  {
    factors[a] = static_cast<unsigned>(std::max(1L, std::lround(targetMm / spacing[a])));
  }
  return factors;
}

Point toPoint(const std::array<double, 3>& p)
{
  Point x;
  x[0] = p[0];
  x[1] = p[1];
  x[2] = p[2];
  return x;
}

std::string firstLine(const itk::ExceptionObject& e)
{
  std::string text = e.GetDescription();
  const auto newline = text.find('\n');
  return newline == std::string::npos ? text : text.substr(0, newline);
}

[[noreturn]] void noOverlap(double fraction)
{
  char text[160];
  std::snprintf(text, sizeof(text),
    "template and patient CT do not overlap after the affine registration: %.0f %% of the "
    "template's region maps into the patient CT",
    100.0 * fraction);
  throw Error(text);
}

/// Fraction of the fixed crop's voxels (every other one) that `map` sends into `patient`.
double overlap(
  const CTVolume& fixed, const CTVolume& patient, const std::function<Point(const Point&)>& map)
{
  double inside = 0.0;
  double count = 0.0;
  for (int k = 0; k < fixed.dims[2]; k += 2)
  {
    for (int j = 0; j < fixed.dims[1]; j += 2)
    {
      for (int i = 0; i < fixed.dims[0]; i += 2)
      {
        const Point y = map(toPoint(fixed.indexToPhysical({ double(i), double(j), double(k) })));
        const std::array<double, 3> index = physicalToIndex(patient, { y[0], y[1], y[2] });
        bool in = true;
        for (int a = 0; a < 3; ++a)
        {
          in = in && index[a] >= -0.5 && index[a] <= patient.dims[a] - 0.5;
        }
        inside += in ? 1.0 : 0.0;
        count += 1.0;
      }
    }
  }
  return count > 0.0 ? inside / count : 0.0;
}

/// Rethrows an ITK failure as a one-line vimlop::Error. "Samples map
/// outside" means the transform has left the moving image: the images do not
/// overlap, and `overlapNow` says by how much.
[[noreturn]] void registrationFailed(const itk::ExceptionObject& e, const std::string& stage,
  const std::function<double()>& overlapNow)
{
  const std::string what = firstLine(e);
  if (what.find("outside") != std::string::npos)
  {
    noOverlap(overlapNow());
  }
  throw Error("the " + stage + " registration failed (" + what + ")");
}

/// Pearson correlation between the fixed crop and the patient at mapped points (stride 2).
double correlation(
  const CTVolume& fixed, const Image* patient, const std::function<Point(const Point&)>& map)
{
  auto interpolator = itk::LinearInterpolateImageFunction<Image, double>::New();
  interpolator->SetInputImage(patient);
  double sa = 0.0, sb = 0.0, saa = 0.0, sbb = 0.0, sab = 0.0, n = 0.0;
  for (int k = 0; k < fixed.dims[2]; k += 2)
  {
    for (int j = 0; j < fixed.dims[1]; j += 2)
    {
      for (int i = 0; i < fixed.dims[0]; i += 2)
      {
        const std::array<double, 3> p = fixed.indexToPhysical({ double(i), double(j), double(k) });
        Point x;
        x[0] = p[0];
        x[1] = p[1];
        x[2] = p[2];
        const Point y = map(x);
        if (!interpolator->IsInsideBuffer(y))
        {
          continue;
        }
        const double a = fixed.intensities[static_cast<std::size_t>(i) +
          static_cast<std::size_t>(fixed.dims[0]) *
            (j + static_cast<std::size_t>(fixed.dims[1]) * k)];
        const double b = interpolator->Evaluate(y);
        sa += a;
        sb += b;
        saa += a * a;
        sbb += b * b;
        sab += a * b;
        n += 1.0;
      }
    }
  }
  if (n < 2.0)
  {
    return 0.0;
  }
  const double cov = sab / n - (sa / n) * (sb / n);
  const double va = saa / n - (sa / n) * (sa / n);
  const double vb = sbb / n - (sb / n) * (sb / n);
  return va > 0.0 && vb > 0.0 ? cov / std::sqrt(va * vb) : 0.0;
}

/// Samples x -> map(x) - x on the voxel grid of `grid`.
DisplacementField sampleField(const CTVolume& grid, const std::function<Point(const Point&)>& map)
{
  DisplacementField field;
  field.dims = grid.dims;
  field.spacingMm = grid.spacingMm;
  field.originMm = grid.originMm;
  field.direction = grid.direction;
  field.displacements.resize(3 * field.numberOfPoints());
  std::size_t n = 0;
  for (int k = 0; k < grid.dims[2]; ++k)
  {
    for (int j = 0; j < grid.dims[1]; ++j)
    {
      for (int i = 0; i < grid.dims[0]; ++i, ++n)
      {
        const std::array<double, 3> p = grid.indexToPhysical({ double(i), double(j), double(k) });
        Point x;
        x[0] = p[0];
        x[1] = p[1];
        x[2] = p[2];
        const Point y = map(x);
        for (int a = 0; a < 3; ++a)
        {
          field.displacements[3 * n + a] = y[a] - x[a];
        }
      }
    }
  }
  return field;
}

void checkOptions(const TemplateRegistration::Options& o)
{
  auto positive = [](const std::vector<double>& v)
  { return !v.empty() && std::all_of(v.begin(), v.end(), [](double x) { return x > 0.0; }); };
  auto counts = [](const std::vector<int>& v)
  { return std::all_of(v.begin(), v.end(), [](int x) { return x >= 0; }); };
  if (!positive(o.affineLevelSpacingMm) ||
    o.affineIterations.size() != o.affineLevelSpacingMm.size() || !counts(o.affineIterations) ||
    !positive(o.synLevelSpacingMm) || o.synIterations.size() != o.synLevelSpacingMm.size() ||
    !counts(o.synIterations))
  {
    throw Error("registration options: each stage needs one positive voxel size and one "
                "non-negative iteration count per level");
  }
  if (o.histogramBins < 4 || !(o.affineSamplingFraction > 0.0 && o.affineSamplingFraction <= 1.0) ||
    !(o.synLearningRate > 0.0) || o.updateFieldVariance < 0.0 || o.totalFieldVariance < 0.0 ||
    !(o.marginMm >= 0.0))
  {
    throw Error("registration options out of range (histogram bins >= 4, sampling fraction in (0, "
                "1], positive learning rate, non-negative variances and margin)");
  }
  if (!(o.regionMm[0] <= o.regionMm[1] && o.regionMm[2] <= o.regionMm[3] &&
        o.regionMm[4] <= o.regionMm[5]))
  {
    throw Error("the region to register is empty");
  }
}

void checkVolume(const CTVolume& v, const std::string& name)
{
  if (v.dims[0] < 4 || v.dims[1] < 4 || v.dims[2] < 4 || v.intensities.size() != v.numberOfVoxels())
  {
    throw Error("the " + name + " CT is not a 3-D volume (" + std::to_string(v.dims[0]) + " x " +
      std::to_string(v.dims[1]) + " x " + std::to_string(v.dims[2]) + " voxels)");
  }
}

} // namespace

TemplateRegistration TemplateRegistration::compute(const CTVolume& templateCT,
  const CTVolume& patientCT, const Options& options, const ProgressCallback& progress)
{
  checkVolume(templateCT, "template");
  checkVolume(patientCT, "patient");
  checkOptions(options);
  TemplateRegistration result;

  // 1. The template crop and the clamped patient.
  std::array<double, 6> region = options.regionMm;
  for (int a = 0; a < 3; ++a)
  {
    region[2 * a] -= options.marginMm;
    region[2 * a + 1] += options.marginMm;
  }
  CTVolume fixedVolume;
  try
  {
    fixedVolume = cropVolume(templateCT, region, kLowestHU, kHighestHU);
  }
  catch (const Error&)
  {
    throw Error("the region to register lies outside the template CT");
  }
  if (fixedVolume.dims[0] < 4 || fixedVolume.dims[1] < 4 || fixedVolume.dims[2] < 4)
  {
    throw Error(
      "the region to register is too thin (under 4 voxels along an axis of the template CT)");
  }
  result.templateCropMm = volumeBounds(fixedVolume);
  const CTVolume movingVolume =
    cropVolume(patientCT, volumeBounds(patientCT), kLowestHU, kHighestHU);
  Image::Pointer fixed = itkconv::toITKImage<Image>(fixedVolume);
  Image::Pointer moving = itkconv::toITKImage<Image>(movingVolume);
  reportProgress(progress, 0.01, "affine registration");

  // 2. Affine.
  const auto affineStart = Clock::now();
  auto affine = AffineTransform::New();
  {
    const std::array<double, 3> centre =
      fixedVolume.indexToPhysical({ 0.5 * (fixedVolume.dims[0] - 1),
        0.5 * (fixedVolume.dims[1] - 1), 0.5 * (fixedVolume.dims[2] - 1) });
    affine->SetCenter(toPoint(centre));
    const std::array<double, 3> from = tissueCentroid(templateCT);
    const std::array<double, 3> to = tissueCentroid(patientCT);
    AffineTransform::OutputVectorType shift;
    for (int a = 0; a < 3; ++a)
    {
      shift[a] = to[a] - from[a];
    }
    affine->SetTranslation(shift);
  }
  result.initialCorrelation =
    correlation(fixedVolume, moving, [&](const Point& x) { return affine->TransformPoint(x); });

  using MIMetric = itk::MattesMutualInformationImageToImageMetricv4<Image, Image>;
  using AffineMethod = itk::ImageRegistrationMethodv4<Image, Image, AffineTransform>;
  const std::size_t affineLevels = options.affineLevelSpacingMm.size();
  {
    auto metric = MIMetric::New();
    metric->SetNumberOfHistogramBins(static_cast<itk::SizeValueType>(options.histogramBins));
    auto scales = itk::RegistrationParameterScalesFromPhysicalShift<MIMetric>::New();
    scales->SetMetric(metric);
    auto optimizer = itk::RegularStepGradientDescentOptimizerv4<double>::New();
    // Steps of up to 2 mm of voxel shift at first (the scales make parameter
    // steps comparable to shifts), halved whenever the direction turns back.
    optimizer->SetLearningRate(2.0);
    optimizer->SetMinimumStepLength(1e-3);
    optimizer->SetRelaxationFactor(0.5);
    optimizer->SetGradientMagnitudeTolerance(1e-6);
    optimizer->SetScalesEstimator(scales);
    optimizer->SetNumberOfIterations(static_cast<itk::SizeValueType>(options.affineIterations[0]));

    auto method = AffineMethod::New();
    method->SetFixedImage(fixed);
    method->SetMovingImage(moving);
    method->SetInitialTransform(affine);
    method->InPlaceOn();
    method->SetMetric(metric);
    method->SetOptimizer(optimizer);
    method->SetNumberOfLevels(affineLevels);
    AffineMethod::SmoothingSigmasArrayType sigmas(static_cast<unsigned>(affineLevels));
    for (std::size_t level = 0; level < affineLevels; ++level)
    {
      method->SetShrinkFactorsPerDimension(static_cast<unsigned>(level),
        shrinkFactors(fixedVolume.spacingMm, options.affineLevelSpacingMm[level]));
      // Smooth to about the level's voxel size before sampling it.
      sigmas[static_cast<unsigned>(level)] = 0.5 * options.affineLevelSpacingMm[level];
    }
    method->SetSmoothingSigmasPerLevel(sigmas);
    method->SmoothingSigmasAreSpecifiedInPhysicalUnitsOn();
    method->SetMetricSamplingStrategy(AffineMethod::MetricSamplingStrategyEnum::REGULAR);
    method->SetMetricSamplingPercentage(options.affineSamplingFraction);
    method->MetricSamplingReinitializeSeed(7);

    double total = 0.0;
    for (int n : options.affineIterations)
    {
      total += n;
    }
    auto levelObserver = Observer::New();
    levelObserver->Callback = [&]()
    {
      const auto level = static_cast<std::size_t>(method->GetCurrentLevel());
      if (level < affineLevels)
      {
        optimizer->SetNumberOfIterations(
          static_cast<itk::SizeValueType>(options.affineIterations[level]));
      }
    };
    method->AddObserver(itk::MultiResolutionIterationEvent(), levelObserver);
    auto iterationObserver = Observer::New();
    iterationObserver->Callback = [&]()
    {
      double done = optimizer->GetCurrentIteration();
      for (std::size_t level = 0;
           level < std::min<std::size_t>(method->GetCurrentLevel(), affineLevels); ++level)
      {
        done += options.affineIterations[level];
      }
      reportProgress(
        progress, 0.01 + 0.19 * std::min(1.0, done / std::max(1.0, total)), "affine registration");
    };
    optimizer->AddObserver(itk::IterationEvent(), iterationObserver);
    try
    {
      method->Update();
    }
    catch (const itk::ExceptionObject& e)
    {
      registrationFailed(e, "affine",
        [&]
        {
          return overlap(
            fixedVolume, patientCT, [&](const Point& x) { return affine->TransformPoint(x); });
        });
    }
    result.affineMetricValue = optimizer->GetValue();
  }
  for (int row = 0; row < 3; ++row)
  {
    for (int col = 0; col < 3; ++col)
    {
      result.affine[4 * row + col] = affine->GetMatrix()(row, col);
    }
    result.affine[4 * row + 3] = affine->GetOffset()[row];
  }
  result.affineSeconds = seconds(affineStart);
  result.affineCorrelation =
    correlation(fixedVolume, moving, [&](const Point& x) { return affine->TransformPoint(x); });

  // 3. Overlap.
  result.overlapFraction =
    overlap(fixedVolume, patientCT, [&](const Point& x) { return affine->TransformPoint(x); });
  if (result.overlapFraction < options.minimumOverlap)
  {
    noOverlap(result.overlapFraction);
  }

  // 4. SyN on the patient crop that covers the affinely mapped template crop.
  reportProgress(progress, 0.2, "deformable registration");
  const auto synStart = Clock::now();
  std::array<double, 6> mapped{ std::numeric_limits<double>::max(),
    -std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
    -std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
    -std::numeric_limits<double>::max() };
  for (int corner = 0; corner < 8; ++corner)
  {
    const Point y = affine->TransformPoint(toPoint({ result.templateCropMm[(corner & 1) ? 1 : 0],
      result.templateCropMm[(corner & 2) ? 3 : 2], result.templateCropMm[(corner & 4) ? 5 : 4] }));
    for (int a = 0; a < 3; ++a)
    {
      mapped[2 * a] = std::min(mapped[2 * a], y[a] - options.marginMm);
      mapped[2 * a + 1] = std::max(mapped[2 * a + 1], y[a] + options.marginMm);
    }
  }
  const CTVolume patientVolume = cropVolume(patientCT, mapped, kLowestHU, kHighestHU);
  moving = itkconv::toITKImage<Image>(patientVolume);

  using SyN = itk::SyNImageRegistrationMethod<Image, Image, FieldTransform>;
  auto syn = SyN::New();
  const std::size_t synLevels = options.synLevelSpacingMm.size();
  {
    syn->SetFixedImage(fixed);
    syn->SetMovingImage(moving);
    syn->SetMovingInitialTransform(affine);
    // The level adaptors resample the output transform's field at every
    // level, the first included, so it starts as a zero field on the crop.
    auto zero = FieldTransform::DisplacementFieldType::New();
    zero->CopyInformation(fixed);
    zero->SetRegions(fixed->GetLargestPossibleRegion());
    zero->Allocate();
    zero->FillBuffer(FieldTransform::DisplacementFieldType::PixelType(0.0));
    auto output = FieldTransform::New();
    output->SetDisplacementField(zero);
    syn->SetInitialTransform(output);
    syn->InPlaceOn();
    if (options.metric == Metric::MeanSquares)
    {
      syn->SetMetric(itk::MeanSquaresImageToImageMetricv4<Image, Image>::New());
    }
    else
    {
      auto metric = MIMetric::New();
      metric->SetNumberOfHistogramBins(static_cast<itk::SizeValueType>(options.histogramBins));
      syn->SetMetric(metric);
    }
    syn->SetNumberOfLevels(synLevels);
    SyN::SmoothingSigmasArrayType sigmas(static_cast<unsigned>(synLevels));
    SyN::NumberOfIterationsArrayType iterations(static_cast<unsigned>(synLevels));
    SyN::TransformParametersAdaptorsContainerType adaptors;
    for (std::size_t level = 0; level < synLevels; ++level)
    {
      const auto factors = shrinkFactors(fixedVolume.spacingMm, options.synLevelSpacingMm[level]);
      syn->SetShrinkFactorsPerDimension(static_cast<unsigned>(level), factors);
      // No smoothing at the finest level: its detail is what SyN is for.
      sigmas[static_cast<unsigned>(level)] =
        level + 1 == synLevels ? 0.0 : 0.5 * options.synLevelSpacingMm[level];
      iterations[static_cast<unsigned>(level)] =
        static_cast<itk::SizeValueType>(options.synIterations[level]);
      // The field of each level lives on the shrunk template crop.
      auto shrink = itk::ShrinkImageFilter<Image, Image>::New();
      shrink->SetShrinkFactors(factors);
      shrink->SetInput(fixed);
      shrink->UpdateOutputInformation();
      const Image* shrunk = shrink->GetOutput();
      auto adaptor = itk::DisplacementFieldTransformParametersAdaptor<FieldTransform>::New();
      adaptor->SetRequiredSpacing(shrunk->GetSpacing());
      adaptor->SetRequiredSize(shrunk->GetLargestPossibleRegion().GetSize());
      adaptor->SetRequiredDirection(shrunk->GetDirection());
      adaptor->SetRequiredOrigin(shrunk->GetOrigin());
      adaptors.push_back(adaptor);
    }
    syn->SetSmoothingSigmasPerLevel(sigmas);
    syn->SmoothingSigmasAreSpecifiedInPhysicalUnitsOn();
    syn->SetNumberOfIterationsPerLevel(iterations);
    syn->SetTransformParametersAdaptorsPerLevel(adaptors);
    syn->SetLearningRate(options.synLearningRate);
    syn->SetConvergenceThreshold(1e-6);
    syn->SetConvergenceWindowSize(10);
    syn->SetGaussianSmoothingVarianceForTheUpdateField(options.updateFieldVariance);
    syn->SetGaussianSmoothingVarianceForTheTotalField(options.totalFieldVariance);

    // Progress: a level's iterations cost about its number of voxels.
    std::vector<double> cost(synLevels);
    double total = 0.0;
    for (std::size_t level = 0; level < synLevels; ++level)
    {
      const auto factors = shrinkFactors(fixedVolume.spacingMm, options.synLevelSpacingMm[level]);
      cost[level] =
        static_cast<double>(fixedVolume.numberOfVoxels()) / (factors[0] * factors[1] * factors[2]);
      total += cost[level] * options.synIterations[level];
    }
    auto iterationObserver = Observer::New();
    iterationObserver->Callback = [&]()
    {
      const auto level = std::min<std::size_t>(syn->GetCurrentLevel(), synLevels - 1);
      double done = cost[level] * syn->GetCurrentIteration();
      for (std::size_t l = 0; l < level; ++l)
      {
        done += cost[l] * options.synIterations[l];
      }
      reportProgress(progress, 0.2 + 0.75 * std::min(1.0, done / std::max(1.0, total)),
        "deformable registration");
    };
    syn->AddObserver(itk::IterationEvent(), iterationObserver);
    try
    {
      syn->Update();
    }
    catch (const itk::ExceptionObject& e)
    {
      registrationFailed(e, "deformable", [&] { return result.overlapFraction; });
    }
    result.synMetricValue = syn->GetCurrentMetricValue();
  }
  FieldTransform* phi = syn->GetModifiableTransform();
  result.synSeconds = seconds(synStart);

  // 5. The fields.
  reportProgress(progress, 0.95, "sampling the fields");
  const auto forward = [&](const Point& x)
  { return affine->TransformPoint(phi->TransformPoint(x)); };
  result.templateToPatient = sampleField(fixedVolume, forward);
  auto affineInverse = AffineTransform::New();
  affine->GetInverse(affineInverse);
  FieldTransform::Pointer phiInverse = FieldTransform::New();
  phiInverse->SetDisplacementField(phi->GetModifiableInverseDisplacementField());
  phiInverse->SetInverseDisplacementField(phi->GetModifiableDisplacementField());
  result.patientToTemplate = sampleField(patientVolume,
    [&](const Point& y) { return phiInverse->TransformPoint(affineInverse->TransformPoint(y)); });
  result.finalCorrelation = correlation(fixedVolume, moving, forward);
  if (result.finalCorrelation < options.warningCorrelation)
  {
    char text[200];
    std::snprintf(text, sizeof(text),
      "the registration may be poor: the correlation of template and patient intensities is %.2f "
      "after it (%.2f after the affine stage; Mattes mutual information %.3f)",
      result.finalCorrelation, result.affineCorrelation, result.affineMetricValue);
    result.warnings.push_back(text);
  }
  reportProgress(progress, 1.0, "done");
  return result;
}

} // namespace vimlop
