// The SyN stage of TemplateRegistration: the only translation unit that
// instantiates ITK's SyN registration method.
#include <vimlop/Imaging/TemplateSyNStage.h>

#include <itkANTSNeighborhoodCorrelationImageToImageMetricv4.h>
#include <itkDisplacementFieldTransformParametersAdaptor.h>
#include <itkMattesMutualInformationImageToImageMetricv4.h>
#include <itkMeanSquaresImageToImageMetricv4.h>
#include <itkShrinkImageFilter.h>
#include <itkSyNImageRegistrationMethod.h>

#include <algorithm>
#include <vector>

namespace vimlop::templatereg
{

TemplateSyNStage TemplateSyNStage::compute(const CTVolume& fixedVolume, const Image* fixed,
  const Image* moving, const InitialTransform* initial, double overlapFraction,
  const TemplateRegistrationOptions& options, const ProgressCallback& progress)
{
  using SyN = itk::SyNImageRegistrationMethod<Image, Image, FieldTransform>;
  auto syn = SyN::New();
  const std::size_t synLevels = options.synLevelSpacingMm.size();
  syn->SetFixedImage(fixed);
  syn->SetMovingImage(moving);
  syn->SetMovingInitialTransform(initial);
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
  if (options.metric == TemplateRegistrationMetric::MeanSquares)
  {
    syn->SetMetric(itk::MeanSquaresImageToImageMetricv4<Image, Image>::New());
  }
  else if (options.metric == TemplateRegistrationMetric::NeighborhoodCorrelation)
  {
    auto metric = itk::ANTSNeighborhoodCorrelationImageToImageMetricv4<Image, Image>::New();
    itk::Size<3> radius;
    radius.Fill(static_cast<itk::SizeValueType>(options.correlationRadiusVoxels));
    metric->SetRadius(radius);
    syn->SetMetric(metric);
  }
  else
  {
    auto metric = itk::MattesMutualInformationImageToImageMetricv4<Image, Image>::New();
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
  syn->AddObserver(itk::IterationEvent(),
    [&](const itk::EventObject&)
    {
      const auto level = std::min<std::size_t>(syn->GetCurrentLevel(), synLevels - 1);
      double done = cost[level] * syn->GetCurrentIteration();
      for (std::size_t l = 0; l < level; ++l)
      {
        done += cost[l] * options.synIterations[l];
      }
      reportProgress(progress, 0.2 + 0.75 * std::min(1.0, done / std::max(1.0, total)),
        "deformable registration");
    });
  try
  {
    syn->Update();
  }
  catch (const itk::ExceptionObject& e)
  {
    registrationFailed(e, "deformable", [&] { return overlapFraction; });
  }
  TemplateSyNStage stage;
  stage.metricValue = syn->GetCurrentMetricValue();
  stage.phi = syn->GetModifiableTransform();
  return stage;
}

} // namespace vimlop::templatereg
