// The B-spline stage of TemplateRegistration: its levels, L-BFGS over the
// cost of BSplineMutualInformationCost.h, and the field it leaves.
#include <vimlop/Imaging/TemplateBSplineStage.h>

#include <vimlop/Imaging/BSplineMutualInformationCost.h>

#include <itkBSplineTransform.h>
#include <itkBSplineTransformParametersAdaptor.h>
#include <itkImageRegionIteratorWithIndex.h>
#include <itkInvertDisplacementFieldImageFilter.h>
#include <itkSmoothingRecursiveGaussianImageFilter.h>
#include <vnl/algo/vnl_lbfgs.h>

#include <algorithm>
#include <cmath>
#include <vector>

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

/// `image` smoothed by a Gaussian of `sigmaMm` (recursive filter, physical units).
Image::Pointer smoothed(const Image* image, double sigmaMm)
{
  auto filter = itk::SmoothingRecursiveGaussianImageFilter<Image, Image>::New();
  filter->SetInput(image);
  filter->SetSigma(sigmaMm);
  filter->Update();
  return filter->GetOutput();
}

} // namespace

TemplateBSplineStage TemplateBSplineStage::compute(const CTVolume& fixedVolume, const Image* fixed,
  const Image* moving, const AffineTransform* affine, double overlapFraction,
  const TemplateRegistrationOptions& options, const ProgressCallback& progress)
{
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
  double affineRows[3][4];
  for (unsigned r = 0; r < 3; ++r)
  {
    for (unsigned c = 0; c < 3; ++c)
    {
      affineRows[r][c] = affine->GetMatrix()[r][c];
    }
    affineRows[r][3] = affine->GetOffset()[r];
  }
  double metricValue = 0.0;
  try
  {
    for (std::size_t level = 0; level < levels; ++level)
    {
      reportProgress(progress, 0.2 + 0.3 * double(level) / double(levels), "B-spline registration");
      if (level > 0)
      {
        auto adaptor = itk::BSplineTransformParametersAdaptor<BSpline>::New();
        adaptor->SetTransform(bspline);
        adaptor->SetRequiredTransformDomainOrigin(bspline->GetTransformDomainOrigin());
        adaptor->SetRequiredTransformDomainDirection(bspline->GetTransformDomainDirection());
        adaptor->SetRequiredTransformDomainPhysicalDimensions(
          bspline->GetTransformDomainPhysicalDimensions());
        adaptor->SetRequiredTransformDomainMeshSize(meshSize(fixed, options.bsplineGridMm[level]));
        adaptor->AdaptTransformParameters();
      }
      const int iterations = options.bsplineIterations[level];
      if (iterations == 0)
      {
        continue;
      }
      // Both images smoothed as ITK's registration method does at a level of
      // this voxel size; the samples are as many as that level has voxels
      // times the sampling fraction, drawn from the full-resolution grid.
      const double levelMm = options.bsplineLevelSpacingMm[level];
      const auto factors = shrinkFactors(fixedVolume.spacingMm, levelMm);
      const double levelVoxels = double(fixed->GetLargestPossibleRegion().GetNumberOfPixels()) /
        (double(factors[0]) * factors[1] * factors[2]);
      const Image::Pointer fixedLevel = smoothed(fixed, 0.5 * levelMm);
      const Image::Pointer movingLevel = smoothed(moving, 0.5 * levelMm);
      BSplineGrid grid;
      {
        const auto* coefficients = bspline->GetCoefficientImages()[0].GetPointer();
        for (unsigned a = 0; a < 3; ++a)
        {
          grid.size[a] = static_cast<long>(coefficients->GetLargestPossibleRegion().GetSize()[a]);
          grid.spacingMm[a] = coefficients->GetSpacing()[a];
        }
      }
      BSplineMutualInformationCost cost(
        drawBSplineSamples(fixedLevel, bspline->GetCoefficientImages()[0],
          static_cast<std::size_t>(options.bsplineSamplingFraction * levelVoxels),
          7u + static_cast<unsigned>(level)),
        movingLevel, affineRows, grid, options.histogramBins, options.bsplineBendingWeightMm2);
      vnl_lbfgs optimizer(cost);
      optimizer.set_max_function_evals(iterations);
      // No early stop on a small gradient: each level runs its evaluations
      // (the gradient of mutual information shrinks with the control
      // spacing, so a relative tolerance stopped the finest level after a
      // few steps).
      optimizer.set_g_tolerance(1e-12);
      vnl_vector<double> x(bspline->GetParameters().data_block(),
        static_cast<unsigned>(bspline->GetNumberOfParameters()));
      optimizer.minimize(x);
      BSpline::ParametersType parameters(x.size());
      std::copy(x.begin(), x.end(), parameters.begin());
      bspline->SetParametersByValue(parameters);
      metricValue = optimizer.get_end_error();
    }
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
  stage.metricValue = metricValue;
  return stage;
}

} // namespace vimlop::templatereg
