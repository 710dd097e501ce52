// The B-spline stage of TemplateRegistration: the only translation unit that
// instantiates ITK's B-spline registration.
#include <vimlop/Imaging/TemplateBSplineStage.h>

#include <itkBSplineTransform.h>
#include <itkBSplineTransformParametersAdaptor.h>
#include <itkImageRegionIteratorWithIndex.h>
#include <itkImageRegistrationMethodv4.h>
#include <itkInvertDisplacementFieldImageFilter.h>
#include <itkLBFGSOptimizerv4.h>
#include <itkMattesMutualInformationImageToImageMetricv4.h>

#include <algorithm>
#include <cmath>

namespace vimlop::templatereg
{

namespace
{

using BSpline = itk::BSplineTransform<double, 3, 3>;

/// Spacing of the samples of the B-spline's displacement field (mm).
constexpr double kFieldSpacingMm = 1.0;

/// Distance between the first and last voxel centres of `image` along axis `a` (mm).
double extentMm(const Image* image, unsigned a)
{
  return image->GetSpacing()[a] * (image->GetLargestPossibleRegion().GetSize()[a] - 1);
}

/// Mesh cells of a control grid `gridMm` apart over the physical extent of `image`.
BSpline::MeshSizeType meshSize(const Image* image, double gridMm)
{
  BSpline::MeshSizeType cells;
  for (unsigned a = 0; a < 3; ++a)
  {
    cells[a] = static_cast<unsigned>(std::max(1.0, std::round(extentMm(image, a) / gridMm)));
  }
  return cells;
}

} // namespace

TemplateBSplineStage TemplateBSplineStage::compute(const CTVolume& fixedVolume, const Image* fixed,
  const Image* moving, const AffineTransform* affine, double overlapFraction,
  const TemplateRegistrationOptions& options, const ProgressCallback& progress)
{
  using Method = itk::ImageRegistrationMethodv4<Image, Image, BSpline>;
  const std::size_t levels = options.bsplineGridMm.size();
  auto bspline = BSpline::New();
  {
    // The domain: the fixed crop's box, on the coarsest grid.
    BSpline::PhysicalDimensionsType dimensions;
    for (unsigned a = 0; a < 3; ++a)
    {
      dimensions[a] = extentMm(fixed, a);
    }
    bspline->SetTransformDomainOrigin(fixed->GetOrigin());
    bspline->SetTransformDomainDirection(fixed->GetDirection());
    bspline->SetTransformDomainPhysicalDimensions(dimensions);
    bspline->SetTransformDomainMeshSize(meshSize(fixed, options.bsplineGridMm[0]));
    bspline->SetIdentity();
  }
  auto method = Method::New();
  method->SetFixedImage(fixed);
  method->SetMovingImage(moving);
  method->SetMovingInitialTransform(affine);
  method->SetInitialTransform(bspline);
  method->InPlaceOn();
  auto metric = itk::MattesMutualInformationImageToImageMetricv4<Image, Image>::New();
  metric->SetNumberOfHistogramBins(static_cast<itk::SizeValueType>(options.histogramBins));
  method->SetMetric(metric);
  auto optimizer = itk::LBFGSOptimizerv4::New();
  optimizer->SetGradientConvergenceTolerance(1e-5);
  optimizer->SetMaximumNumberOfFunctionEvaluations(
    static_cast<unsigned>(options.bsplineIterations[0]));
  method->SetOptimizer(optimizer);
  method->SetNumberOfLevels(levels);
  Method::SmoothingSigmasArrayType sigmas(static_cast<unsigned>(levels));
  Method::TransformParametersAdaptorsContainerType adaptors;
  for (std::size_t level = 0; level < levels; ++level)
  {
    const auto factors = shrinkFactors(fixedVolume.spacingMm, options.bsplineLevelSpacingMm[level]);
    method->SetShrinkFactorsPerDimension(static_cast<unsigned>(level), factors);
    sigmas[static_cast<unsigned>(level)] = 0.5 * options.bsplineLevelSpacingMm[level];
    auto adaptor = itk::BSplineTransformParametersAdaptor<BSpline>::New();
    adaptor->SetTransform(bspline);
    adaptor->SetRequiredTransformDomainOrigin(bspline->GetTransformDomainOrigin());
    adaptor->SetRequiredTransformDomainDirection(bspline->GetTransformDomainDirection());
    adaptor->SetRequiredTransformDomainPhysicalDimensions(
      bspline->GetTransformDomainPhysicalDimensions());
    adaptor->SetRequiredTransformDomainMeshSize(meshSize(fixed, options.bsplineGridMm[level]));
    adaptors.push_back(adaptor);
  }
  method->SetSmoothingSigmasPerLevel(sigmas);
  method->SmoothingSigmasAreSpecifiedInPhysicalUnitsOn();
  method->SetTransformParametersAdaptorsPerLevel(adaptors);
  method->SetMetricSamplingStrategy(Method::MetricSamplingStrategyEnum::RANDOM);
  method->SetMetricSamplingPercentage(options.bsplineSamplingFraction);
  method->MetricSamplingReinitializeSeed(7);
  method->AddObserver(itk::MultiResolutionIterationEvent(),
    [&](const itk::EventObject&)
    {
      const auto level = static_cast<std::size_t>(method->GetCurrentLevel());
      if (level < levels)
      {
        optimizer->SetMaximumNumberOfFunctionEvaluations(
          static_cast<unsigned>(options.bsplineIterations[level]));
      }
      reportProgress(progress, 0.2 + 0.3 * double(level) / double(levels), "B-spline registration");
    });
  try
  {
    method->Update();
  }
  catch (const itk::ExceptionObject& e)
  {
    registrationFailed(e, "B-spline", [&] { return overlapFraction; });
  }

  // Sampled as a displacement field, with its inverse, on the fixed crop's
  // box at about 1 mm: the B-spline is smooth (linear interpolation between
  // 1 mm samples of a field with a 10 mm grid errs by about 0.01 mm), and
  // sampling and inverting at the CT's own voxels would cost more than the
  // registration.
  using Field = FieldTransform::DisplacementFieldType;
  auto field = Field::New();
  {
    const auto factors = shrinkFactors(fixedVolume.spacingMm, kFieldSpacingMm);
    Field::SpacingType spacing;
    Field::SizeType size;
    for (unsigned a = 0; a < 3; ++a)
    {
      spacing[a] = fixed->GetSpacing()[a] * factors[a];
      size[a] = (fixed->GetLargestPossibleRegion().GetSize()[a] - 1) / factors[a] + 1;
    }
    field->SetOrigin(fixed->GetOrigin());
    field->SetDirection(fixed->GetDirection());
    field->SetSpacing(spacing);
    field->SetRegions(size);
  }
  field->Allocate();
  for (itk::ImageRegionIteratorWithIndex<Field> it(field, field->GetLargestPossibleRegion());
       !it.IsAtEnd(); ++it)
  {
    Point x;
    field->TransformIndexToPhysicalPoint(it.GetIndex(), x);
    it.Set(bspline->TransformPoint(x) - x);
  }
  auto invert = itk::InvertDisplacementFieldImageFilter<Field>::New();
  invert->SetInput(field);
  invert->SetMaximumNumberOfIterations(50);
  invert->SetMeanErrorToleranceThreshold(0.001);
  invert->SetMaxErrorToleranceThreshold(0.1);
  invert->Update();
  TemplateBSplineStage stage;
  stage.field = FieldTransform::New();
  stage.field->SetDisplacementField(field);
  stage.field->SetInverseDisplacementField(invert->GetOutput());
  stage.metricValue = optimizer->GetValue();
  return stage;
}

} // namespace vimlop::templatereg
