// Template-to-patient registration with ITK: the driver, and the helpers it
// shares with the affine stage (TemplateAffineStage.cxx) and the SyN stage
// (TemplateSyNStage.cxx). ITK's heavy v4 registration templates live in the
// two stages' units only; all of it is instantiated for float images only.
#include <vimlop/Imaging/TemplateRegistration.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/ITKImageConversion.h>
#include <vimlop/Imaging/TemplateAffineStage.h>
#include <vimlop/Imaging/TemplateBSplineStage.h>
#include <vimlop/Imaging/TemplateRegistrationITK.h>
#include <vimlop/Imaging/TemplateSyNStage.h>
#include <vimlop/Imaging/VolumeCrop.h>

#include <itkCompositeTransform.h>
#include <itkLinearInterpolateImageFunction.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace vimlop
{

namespace templatereg
{

namespace
{

std::string firstLine(const itk::ExceptionObject& e)
{
  std::string text = e.GetDescription();
  const auto newline = text.find('\n');
  return newline == std::string::npos ? text : text.substr(0, newline);
}

} // namespace

Point toPoint(const std::array<double, 3>& p)
{
  Point x;
  x[0] = p[0];
  x[1] = p[1];
  x[2] = p[2];
  return x;
}

itk::FixedArray<unsigned, 3> shrinkFactors(const std::array<double, 3>& spacingMm, double targetMm)
{
  itk::FixedArray<unsigned, 3> factors;
  for (unsigned a = 0; a < 3; ++a)
  {
    factors[a] = static_cast<unsigned>(std::max(1L, std::lround(targetMm / spacingMm[a])));
  }
  return factors;
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

double overlap(const CTVolume& fixed, const CTVolume& patient, const PointMap& map)
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
        const std::array<double, 3> index = patient.physicalToIndex({ y[0], y[1], y[2] });
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

double correlation(const CTVolume& fixed, const Image* patient, const PointMap& map)
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

} // namespace templatereg

namespace
{

using namespace templatereg;
using Clock = std::chrono::steady_clock;

constexpr float kLowestHU = -1000.0f;
constexpr float kHighestHU = 2000.0f;

double seconds(Clock::time_point since)
{
  return std::chrono::duration<double>(Clock::now() - since).count();
}

/// Samples x -> map(x) - x on the voxel grid of `grid`.
DisplacementField sampleField(const CTVolume& grid, const PointMap& map)
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

void checkOptions(const TemplateRegistrationOptions& o)
{
  auto positive = [](const std::vector<double>& v)
  { return !v.empty() && std::all_of(v.begin(), v.end(), [](double x) { return x > 0.0; }); };
  auto counts = [](const std::vector<int>& v)
  { return std::all_of(v.begin(), v.end(), [](int x) { return x >= 0; }); };
  if (!positive(o.affineLevelSpacingMm) ||
    o.affineIterations.size() != o.affineLevelSpacingMm.size() || !counts(o.affineIterations) ||
    !positive(o.synLevelSpacingMm) || o.synIterations.size() != o.synLevelSpacingMm.size() ||
    !counts(o.synIterations) ||
    !(o.bsplineGridMm.empty() ||
      (positive(o.bsplineGridMm) && o.bsplineLevelSpacingMm.size() == o.bsplineGridMm.size() &&
        positive(o.bsplineLevelSpacingMm) && o.bsplineIterations.size() == o.bsplineGridMm.size() &&
        counts(o.bsplineIterations))))
  {
    throw Error("registration options: each stage needs one positive voxel size and one "
                "non-negative iteration count per level");
  }
  if (o.histogramBins < 4 || !(o.affineSamplingFraction > 0.0 && o.affineSamplingFraction <= 1.0) ||
    !(o.bsplineSamplingFraction > 0.0 && o.bsplineSamplingFraction <= 1.0) ||
    !(o.bsplineBendingWeightMm2 >= 0.0) || !(o.synLearningRate > 0.0) ||
    o.updateFieldVariance < 0.0 || o.totalFieldVariance < 0.0 || !(o.marginMm >= 0.0) ||
    o.correlationRadiusVoxels < 1)
  {
    throw Error("registration options out of range (histogram bins >= 4, sampling fraction in (0, "
                "1], positive learning rate, non-negative variances and margin, correlation "
                "radius >= 1 voxel, non-negative bending weight)");
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

std::string templateRegistrationMetricName(TemplateRegistrationMetric metric)
{
  switch (metric)
  {
    case TemplateRegistrationMetric::MeanSquares:
      return "ms";
    case TemplateRegistrationMetric::NeighborhoodCorrelation:
      return "cc";
    case TemplateRegistrationMetric::MattesMutualInformation:
      break;
  }
  return "mi";
}

TemplateRegistrationMetric templateRegistrationMetricFromName(const std::string& name)
{
  for (const TemplateRegistrationMetric metric :
    { TemplateRegistrationMetric::MattesMutualInformation, TemplateRegistrationMetric::MeanSquares,
      TemplateRegistrationMetric::NeighborhoodCorrelation })
  {
    if (templateRegistrationMetricName(metric) == name)
    {
      return metric;
    }
  }
  throw Error("unknown SyN metric '" + name + "' (mi, ms or cc)");
}

TemplateRegistration TemplateRegistration::compute(const CTVolume& templateCT,
  const CTVolume& patientCT, const TemplateRegistrationOptions& options,
  const ProgressCallback& progress)
{
  checkVolume(templateCT, "template");
  checkVolume(patientCT, "patient");
  checkOptions(options);
  TemplateRegistration result;
  result.settings = options;

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
  const TemplateAffineStage affineStage = TemplateAffineStage::compute(
    templateCT, patientCT, fixedVolume, fixed, moving, options, progress);
  AffineTransform* affine = affineStage.transform;
  result.initialCorrelation = affineStage.initialCorrelation;
  result.affineMetricValue = affineStage.metricValue;
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

  // 4. SyN (after the B-spline stage, when asked for) on the patient crop
  // that covers the affinely mapped template crop.
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

  // The B-spline stage, when asked for, after the affine map, on the same crops.
  auto initial = itk::CompositeTransform<double, 3>::New();
  initial->AddTransform(affine); // applied last
  FieldTransform::Pointer bspline;
  if (!options.bsplineGridMm.empty())
  {
    const auto bsplineStart = Clock::now();
    bspline = TemplateBSplineStage::compute(
      fixedVolume, fixed, moving, affine, result.overlapFraction, options, progress)
                .field;
    initial->AddTransform(bspline); // applied first
    result.bsplineSeconds = seconds(bsplineStart);
  }

  // The SyN stage reports from 0.2 to 0.95; after a B-spline stage (0.2 to
  // 0.5) from 0.5 on.
  const ProgressCallback synProgress = !bspline
    ? progress
    : ProgressCallback([&](double fraction, const std::string& step)
        { reportProgress(progress, 0.5 + 0.6 * (fraction - 0.2), step); });
  const TemplateSyNStage synStage = TemplateSyNStage::compute(
    fixedVolume, fixed, moving, initial, result.overlapFraction, options, synProgress);
  result.synMetricValue = synStage.metricValue;
  FieldTransform* phi = synStage.phi;
  result.synSeconds = seconds(synStart) - result.bsplineSeconds;

  // 5. The fields.
  reportProgress(progress, 0.95, "sampling the fields");
  const auto forward = [&](const Point& x)
  { return initial->TransformPoint(phi->TransformPoint(x)); };
  result.templateToPatient = sampleField(fixedVolume, forward);
  auto affineInverse = AffineTransform::New();
  affine->GetInverse(affineInverse);
  FieldTransform::Pointer phiInverse = FieldTransform::New();
  phiInverse->SetDisplacementField(phi->GetModifiableInverseDisplacementField());
  phiInverse->SetInverseDisplacementField(phi->GetModifiableDisplacementField());
  FieldTransform::Pointer bsplineInverse;
  if (bspline)
  {
    bsplineInverse = FieldTransform::New();
    bsplineInverse->SetDisplacementField(bspline->GetModifiableInverseDisplacementField());
  }
  result.patientToTemplate = sampleField(patientVolume,
    [&](const Point& y)
    {
      Point x = affineInverse->TransformPoint(y);
      if (bsplineInverse)
      {
        x = bsplineInverse->TransformPoint(x);
      }
      return phiInverse->TransformPoint(x);
    });
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
