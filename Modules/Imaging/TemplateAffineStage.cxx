// The affine stage of TemplateRegistration: the only translation unit that
// instantiates ITK's v4 affine registration method.
#include <vimlop/Imaging/TemplateAffineStage.h>

#include <itkImageRegistrationMethodv4.h>
#include <itkMattesMutualInformationImageToImageMetricv4.h>
#include <itkRegistrationParameterScalesFromPhysicalShift.h>
#include <itkRegularStepGradientDescentOptimizerv4.h>

#include <algorithm>

namespace vimlop::templatereg
{

namespace
{

constexpr double kTissueHU = -500.0;

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

/**
 * Mattes mutual information computed in one work unit. With more, ITK 5.2's
 * metric adds each work unit's derivative buffer into the shared one in the
 * order the threads win a lock, so its float sums, and after them the whole
 * warp, differed from run to run of one pair (P4's largest pose error moved
 * by 0.1 degree). The metric's SetMaximumNumberOfWorkUnits() limits threads,
 * not work units, so the work units are set on its threaders here.
 */
class RepeatableMattesMetric : public itk::MattesMutualInformationImageToImageMetricv4<Image, Image>
{
public:
  using Self = RepeatableMattesMetric;
  using Superclass = itk::MattesMutualInformationImageToImageMetricv4<Image, Image>;
  using Pointer = itk::SmartPointer<Self>;
  itkNewMacro(Self);

protected:
  RepeatableMattesMetric()
  {
    this->m_DenseGetValueAndDerivativeThreader->SetNumberOfWorkUnits(1);
    this->m_SparseGetValueAndDerivativeThreader->SetNumberOfWorkUnits(1);
  }
};

} // namespace

TemplateAffineStage TemplateAffineStage::compute(const CTVolume& templateCT,
  const CTVolume& patientCT, const CTVolume& fixedVolume, const Image* fixed, const Image* moving,
  const TemplateRegistrationOptions& options, const ProgressCallback& progress)
{
  TemplateAffineStage stage;
  auto affine = AffineTransform::New();
  stage.transform = affine;
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
  stage.initialCorrelation =
    correlation(fixedVolume, moving, [&](const Point& x) { return affine->TransformPoint(x); });

  using MIMetric = RepeatableMattesMetric;
  using AffineMethod = itk::ImageRegistrationMethodv4<Image, Image, AffineTransform>;
  const std::size_t affineLevels = options.affineLevelSpacingMm.size();
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
  method->AddObserver(itk::MultiResolutionIterationEvent(),
    [&](const itk::EventObject&)
    {
      const auto level = static_cast<std::size_t>(method->GetCurrentLevel());
      if (level < affineLevels)
      {
        optimizer->SetNumberOfIterations(
          static_cast<itk::SizeValueType>(options.affineIterations[level]));
      }
    });
  optimizer->AddObserver(itk::IterationEvent(),
    [&](const itk::EventObject&)
    {
      double done = optimizer->GetCurrentIteration();
      for (std::size_t level = 0;
           level < std::min<std::size_t>(method->GetCurrentLevel(), affineLevels); ++level)
      {
        done += options.affineIterations[level];
      }
      reportProgress(
        progress, 0.01 + 0.19 * std::min(1.0, done / std::max(1.0, total)), "affine registration");
    });
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
  stage.metricValue = optimizer->GetValue();
  return stage;
}

} // namespace vimlop::templatereg
