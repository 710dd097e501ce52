#include <vimlop/Evaluation/TemplateWarpProtocol.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/Peers/ElastixParameterFiles.h>
#include <vimlop/Evaluation/Peers/ElastixRegistration.h>
#include <vimlop/Evaluation/SyntheticDeformation.h>
#include <vimlop/Imaging/AirwaySegmentation.h>
#include <vimlop/Imaging/AirwaySurface.h>
#include <vimlop/Imaging/TemplateRegistration.h>
#include <vimlop/Imaging/TemplateWarpJob.h>
#include <vimlop/Imaging/VolumeCrop.h>

#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

namespace vimlop
{

namespace
{

using Point = std::array<double, 3>;

/// Per-vertex errors and the index of the vertex with the largest.
VertexErrorSummary summarizeErrors(
  const std::vector<Point>& estimate, const std::vector<Point>& truth, std::size_t* worst = nullptr)
{
  std::vector<double> errors(truth.size());
  double sum = 0.0;
  std::size_t largest = 0;
  for (std::size_t i = 0; i < truth.size(); ++i)
  {
    errors[i] = std::hypot(
      estimate[i][0] - truth[i][0], estimate[i][1] - truth[i][1], estimate[i][2] - truth[i][2]);
    sum += errors[i];
    largest = errors[i] > errors[largest] ? i : largest;
  }
  if (worst)
  {
    *worst = largest;
  }
  std::sort(errors.begin(), errors.end());
  VertexErrorSummary s;
  s.meanMm = sum / static_cast<double>(errors.size());
  const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(errors.size())));
  s.p95Mm = errors[std::max<std::size_t>(rank, 1) - 1];
  s.maxMm = errors.back();
  return s;
}

nlohmann::json errorsJson(const VertexErrorSummary& s)
{
  return { { "mean_mm", s.meanMm }, { "p95_mm", s.p95Mm }, { "max_mm", s.maxMm } };
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

void TemplateWarpProtocolOptions::validate() const
{
  if (!(this->maxDisplacementMm > 0.0))
  {
    throw Error("--max-displacement-mm must be positive");
  }
  if (!(this->noiseHU >= 0.0))
  {
    throw Error("--noise-hu must not be negative");
  }
  if (this->runElastix && this->elastixWorkFolder.empty())
  {
    throw Error("P4: elastix needs a work folder");
  }
}

std::string TemplateWarpProtocolReport::summaryText() const
{
  std::string text = formatText("seed %u, %.1f mm: mean %.2f mm, p95 %.2f mm, max %.2f mm, %.1f s "
                                "(before: mean %.2f mm)",
    this->seed, this->maxDisplacementMm, this->errors.meanMm, this->errors.p95Mm,
    this->errors.maxMm, this->runtimeS, this->beforeRegistration.meanMm);
  if (this->elastix)
  {
    const Elastix& e = *this->elastix;
    text += formatText("; elastix mean %.2f mm, p95 %.2f mm, max %.2f mm, %.1f s (%.2fx our time)",
      e.errors.meanMm, e.errors.p95Mm, e.errors.maxMm, e.runtimeS, e.runtimeRatio);
  }
  return text;
}

void TemplateWarpProtocolReport::requireErrorsAtMost(double meanMm, double p95Mm) const
{
  if (meanMm >= 0.0 && this->errors.meanMm > meanMm)
  {
    throw Error(formatText(
      "the mean vertex error %.2f mm exceeds the required %.2f mm", this->errors.meanMm, meanMm));
  }
  if (p95Mm >= 0.0 && this->errors.p95Mm > p95Mm)
  {
    throw Error(formatText("the 95th percentile vertex error %.2f mm exceeds the required %.2f mm",
      this->errors.p95Mm, p95Mm));
  }
}

void TemplateWarpProtocolReport::requireNoWorseThanElastix() const
{
  if (!this->elastix)
  {
    throw Error("elastix did not run (" + this->elastixStatus + "): nothing to compare with");
  }
  if (this->errors.meanMm > this->elastix->errors.meanMm)
  {
    throw Error(formatText("the mean vertex error %.3f mm exceeds elastix's %.3f mm",
      this->errors.meanMm, this->elastix->errors.meanMm));
  }
  if (this->elastix->runtimeRatio < 1.0)
  {
    throw Error(formatText("the registration took %.1f s, longer than elastix's %.1f s",
      this->runtimeS, this->elastix->runtimeS));
  }
}

nlohmann::json TemplateWarpProtocolReport::toJson() const
{
  nlohmann::json report;
  report["protocol"] = "P4 template warp (DESIGN section 6)";
  report["seed"] = this->seed;
  report["max_displacement_mm"] = this->maxDisplacementMm;
  report["control_spacing_mm"] = this->controlSpacingMm;
  report["noise_hu"] = this->noiseHU;
  report["vertices"] = this->vertices;
  report["airway_volume_cm3"] = this->airwayVolumeCm3;
  report["mean_mm"] = this->errors.meanMm;
  report["p95_mm"] = this->errors.p95Mm;
  report["max_mm"] = this->errors.maxMm;
  report["max_at_mm"] = this->maxAtMm;
  report["runtime_s"] = this->runtimeS;
  report["before_registration"] = errorsJson(this->beforeRegistration);
  report["affine_only"] = errorsJson(this->affineOnly);
  report["registration"] = { { "affine_s", this->affineS }, { "bspline_s", this->bsplineS },
    { "syn_s", this->synS }, { "overlap_fraction", this->overlapFraction },
    { "correlation",
      { { "initial", this->initialCorrelation }, { "affine", this->affineCorrelation },
        { "final", this->finalCorrelation } } },
    { "template_crop_mm", this->templateCropMm }, { "settings", settingsJson(this->settings) } };
  if (this->elastix)
  {
    nlohmann::json e = errorsJson(this->elastix->errors);
    e["runtime_s"] = this->elastix->runtimeS;
    e["runtime_ratio"] = this->elastix->runtimeRatio;
    e["parameter_files"] = this->elastix->parameterFiles;
    report["elastix"] = e;
  }
  else
  {
    report["elastix"] = nullptr;
  }
  report["elastix_status"] = this->elastixStatus;
  return report;
}

TemplateWarpProtocolReport runTemplateWarpProtocol(const CTVolume& ct,
  const TemplateWarpProtocolOptions& options, const EvaluationProgress& progress)
{
  namespace fs = std::filesystem;
  options.validate();
  // The stages report fractions; the protocol counts thousandths.
  auto report = [&](double fraction, const std::string& step) {
    reportEvaluationCount(progress, step, static_cast<int>(std::lround(1000.0 * fraction)), 1000);
  };

  // The template and its airway mesh.
  const AirwaySegmentation airway = AirwaySegmentation::compute(
    ct, {}, [&](double f, const std::string& step) { report(0.03 * f, step); });
  const AirwaySurface surface = AirwaySurface::compute(airway.label, {});
  std::vector<Point> vertices(static_cast<std::size_t>(surface.surface->GetNumberOfPoints()));
  std::array<double, 6> region{ 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (std::size_t i = 0; i < vertices.size(); ++i)
  {
    surface.surface->GetPoint(static_cast<vtkIdType>(i), vertices[i].data());
    for (int a = 0; a < 3; ++a)
    {
      region[2 * a] = std::min(region[2 * a], vertices[i][a]);
      region[2 * a + 1] = std::max(region[2 * a + 1], vertices[i][a]);
    }
  }

  // The patient: a known smooth deformation plus noise.
  report(0.04, "making the patient");
  SyntheticDeformationOptions deformationOptions;
  deformationOptions.maxDisplacementMm = options.maxDisplacementMm;
  deformationOptions.controlSpacingMm = options.controlSpacingMm;
  deformationOptions.seed = options.seed;
  deformationOptions.regionMm = region;
  const SyntheticDeformation deformation(ct, deformationOptions);
  const CTVolume patient = deformation.makePatient(ct, options.noiseHU, options.seed + 1000u);
  std::vector<Point> truth(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
  {
    truth[i] = deformation.templateToPatient(vertices[i]);
  }

  TemplateWarpProtocolReport r;
  r.seed = options.seed;
  r.maxDisplacementMm = options.maxDisplacementMm;
  r.controlSpacingMm = options.controlSpacingMm;
  r.noiseHU = options.noiseHU;
  r.vertices = vertices.size();
  r.airwayVolumeCm3 = airway.volumeMm3 / 1000.0;
  r.beforeRegistration = summarizeErrors(vertices, truth);

  // VIMLOP's registration.
  TemplateRegistrationOptions registration = options.registration;
  registration.regionMm = region;
  const auto start = std::chrono::steady_clock::now();
  const TemplateRegistration result = TemplateRegistration::compute(ct, patient, registration,
    [&](double f, const std::string& step) { report(0.05 + 0.6 * f, step); });
  std::vector<Point> warped(vertices.size());
  std::vector<Point> affineOnly(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
  {
    warped[i] = result.templateToPatient.transformPoint(vertices[i]);
    for (int row = 0; row < 3; ++row)
    {
      affineOnly[i][row] = result.affine[4 * row + 3];
      for (int col = 0; col < 3; ++col)
      {
        affineOnly[i][row] += result.affine[4 * row + col] * vertices[i][col];
      }
    }
  }
  r.runtimeS = secondsSince(start);
  std::size_t worst = 0;
  r.errors = summarizeErrors(warped, truth, &worst);
  r.maxAtMm = vertices[worst];
  r.affineOnly = summarizeErrors(affineOnly, truth);
  r.affineS = result.affineSeconds;
  r.synS = result.synSeconds;
  r.bsplineS = result.bsplineSeconds;
  r.settings = result.settings;
  r.overlapFraction = result.overlapFraction;
  r.initialCorrelation = result.initialCorrelation;
  r.affineCorrelation = result.affineCorrelation;
  r.finalCorrelation = result.finalCorrelation;
  r.templateCropMm = result.templateCropMm;
  r.warnings = result.warnings;

  // elastix on the same pair: the same template crop, the patient around it.
  const std::string parameters = options.elastixParametersFolder.empty()
    ? defaultElastixParametersFolder()
    : options.elastixParametersFolder;
  ElastixRegistrationOptions elastix;
  elastix.parameterFiles = { (fs::path(parameters) / "affine.txt").string(),
    (fs::path(parameters) / "bspline.txt").string() };
  elastix.workDirectory = options.elastixWorkFolder;
  if (!options.runElastix)
  {
    r.elastixStatus = "not run (--no-elastix)";
  }
  else if (!ElastixRegistration::available(elastix))
  {
    r.elastixStatus = "not installed";
  }
  else
  {
    report(0.66, "elastix");
    constexpr float low = -1000.0f;
    constexpr float high = 2000.0f;
    std::array<double, 6> around = result.templateCropMm;
    for (int a = 0; a < 3; ++a)
    {
      around[2 * a] -= registration.marginMm;
      around[2 * a + 1] += registration.marginMm;
    }
    const ElastixRegistration peer =
      ElastixRegistration::compute(cropVolume(ct, result.templateCropMm, low, high),
        cropVolume(patient, around, low, high), vertices, elastix);
    TemplateWarpProtocolReport::Elastix e;
    e.errors = summarizeErrors(peer.movingPoints, truth);
    e.runtimeS = peer.registrationSeconds + peer.transformSeconds;
    e.runtimeRatio = e.runtimeS / r.runtimeS;
    e.parameterFiles = elastix.parameterFiles;
    r.elastix = e;
    r.elastixStatus = "ran";
  }
  report(1.0, "done");
  return r;
}

} // namespace vimlop
