#include "EvaluateWarpCommand.h"

#include "AirwaySegmentation.h"
#include "AirwaySurface.h"
#include "CTVolumeIO.h"
#include "ElastixRegistration.h"
#include "Error.h"
#include "SyntheticDeformation.h"
#include "TemplateRegistration.h"
#include "TerminalProgress.h"
#include "VolumeCrop.h"

#include <CLI/CLI.hpp>

#include <nlohmann/json.hpp>

#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

namespace vimlop
{

namespace
{

using Point = std::array<double, 3>;

/// The elastix parameter files: the source tree's while building, else the
/// installed copy next to the program (<prefix>/share/vimlop/elastix).
std::string defaultElastixParameters()
{
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(VIMLOP_ELASTIX_PARAMETERS_DIR, ec))
  {
    return VIMLOP_ELASTIX_PARAMETERS_DIR;
  }
  const fs::path installed =
    fs::read_symlink("/proc/self/exe", ec).parent_path().parent_path() / "share/vimlop/elastix";
  return !ec && fs::is_directory(installed, ec) ? installed.string()
                                                : VIMLOP_ELASTIX_PARAMETERS_DIR;
}

struct EvaluateWarpOptions
{
  std::string ct;
  std::string out;
  double maxDisplacementMm = 5.0;
  double controlSpacingMm = 30.0;
  double noiseHU = 20.0;
  unsigned seed = 1;
  bool noElastix = false;
  std::string elastixParameters = defaultElastixParameters();
  double requireMeanMm = -1.0;
  double requireP95Mm = -1.0;
};

/// Mean, 95th percentile (nearest rank) and maximum of per-vertex errors.
struct ErrorSummary
{
  double mean = 0.0;
  double p95 = 0.0;
  double max = 0.0;
  /// Index of the vertex with the largest error.
  std::size_t worst = 0;
};

ErrorSummary summarize(const std::vector<Point>& estimate, const std::vector<Point>& truth)
{
  std::vector<double> errors(truth.size());
  double sum = 0.0;
  ErrorSummary s;
  for (std::size_t i = 0; i < truth.size(); ++i)
  {
    errors[i] = std::hypot(
      estimate[i][0] - truth[i][0], estimate[i][1] - truth[i][1], estimate[i][2] - truth[i][2]);
    sum += errors[i];
    s.worst = errors[i] > errors[s.worst] ? i : s.worst;
  }
  std::sort(errors.begin(), errors.end());
  s.mean = sum / static_cast<double>(errors.size());
  const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(errors.size())));
  s.p95 = errors[std::max<std::size_t>(rank, 1) - 1];
  s.max = errors.back();
  return s;
}

nlohmann::json toJson(const ErrorSummary& s)
{
  return { { "mean_mm", s.mean }, { "p95_mm", s.p95 }, { "max_mm", s.max } };
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void runEvaluateWarp(const EvaluateWarpOptions& options)
{
  namespace fs = std::filesystem;
  if (!(options.maxDisplacementMm > 0.0))
  {
    throw Error("--max-displacement-mm must be positive");
  }
  if (!(options.noiseHU >= 0.0))
  {
    throw Error("--noise-hu must not be negative");
  }
  const fs::path outPath(options.out);
  if (outPath.extension() != ".json")
  {
    throw Error("'" + options.out + "': the result file must be .json");
  }
  const ProgressCallback progress = terminalProgress("evaluate warp");

  // The template and its airway mesh.
  const CTVolume ct = readCTVolume(options.ct);
  const AirwaySegmentation airway = AirwaySegmentation::compute(
    ct, {}, [&](double f, const std::string& step) { reportProgress(progress, 0.03 * f, step); });
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
  reportProgress(progress, 0.04, "making the patient");
  SyntheticDeformation::Options deformationOptions;
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
  const ErrorSummary before = summarize(vertices, truth);

  // VIMLOP's registration.
  TemplateRegistration::Options registration;
  registration.regionMm = region;
  const auto start = std::chrono::steady_clock::now();
  const TemplateRegistration result = TemplateRegistration::compute(ct, patient, registration,
    [&](double f, const std::string& step) { reportProgress(progress, 0.05 + 0.6 * f, step); });
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
  const double runtime = secondsSince(start);
  const ErrorSummary ours = summarize(warped, truth);
  for (const std::string& warning : result.warnings)
  {
    std::cerr << "vimlop evaluate warp: warning: " << warning << "\n";
  }

  nlohmann::json report;
  report["protocol"] = "P4 template warp (DESIGN section 6)";
  report["ct"] = options.ct;
  report["seed"] = options.seed;
  report["max_displacement_mm"] = options.maxDisplacementMm;
  report["control_spacing_mm"] = options.controlSpacingMm;
  report["noise_hu"] = options.noiseHU;
  report["vertices"] = vertices.size();
  report["airway_volume_cm3"] = airway.volumeMm3 / 1000.0;
  report["mean_mm"] = ours.mean;
  report["p95_mm"] = ours.p95;
  report["max_mm"] = ours.max;
  // Where the largest error is (template frame): typically on the cap that
  // closes the airway where it leaves the CT's field of view, which no image
  // content guides.
  report["max_at_mm"] = vertices[ours.worst];
  report["runtime_s"] = runtime;
  report["before_registration"] = toJson(before);
  report["affine_only"] = toJson(summarize(affineOnly, truth));
  report["registration"] = { { "affine_s", result.affineSeconds }, { "syn_s", result.synSeconds },
    { "overlap_fraction", result.overlapFraction },
    { "correlation",
      { { "initial", result.initialCorrelation }, { "affine", result.affineCorrelation },
        { "final", result.finalCorrelation } } },
    { "template_crop_mm", result.templateCropMm } };

  // elastix on the same pair: the same template crop, the patient around it.
  std::string elastixLine;
  ElastixRegistration::Options elastix;
  elastix.parameterFiles = { (fs::path(options.elastixParameters) / "affine.txt").string(),
    (fs::path(options.elastixParameters) / "bspline.txt").string() };
  elastix.workDirectory = (outPath.parent_path() / (outPath.stem().string() + "-elastix")).string();
  if (options.noElastix)
  {
    report["elastix"] = nullptr;
    report["elastix_status"] = "not run (--no-elastix)";
  }
  else if (!ElastixRegistration::available(elastix))
  {
    report["elastix"] = nullptr;
    report["elastix_status"] = "not installed";
  }
  else
  {
    reportProgress(progress, 0.66, "elastix");
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
    const ErrorSummary theirs = summarize(peer.movingPoints, truth);
    const double elastixRuntime = peer.registrationSeconds + peer.transformSeconds;
    nlohmann::json e = toJson(theirs);
    e["runtime_s"] = elastixRuntime;
    e["runtime_ratio"] = elastixRuntime / runtime;
    e["parameter_files"] = elastix.parameterFiles;
    report["elastix"] = e;
    report["elastix_status"] = "ran";
    char text[200];
    std::snprintf(text, sizeof(text),
      "; elastix mean %.2f mm, p95 %.2f mm, max %.2f mm, %.1f s (%.2fx our time)", theirs.mean,
      theirs.p95, theirs.max, elastixRuntime, elastixRuntime / runtime);
    elastixLine = text;
  }
  reportProgress(progress, 1.0, "done");
  {
    std::ofstream out(outPath);
    out << report.dump(2) << "\n";
    if (!out)
    {
      throw Error("'" + options.out + "': could not write the result");
    }
  }
  std::printf("vimlop evaluate warp: seed %u, %.1f mm: mean %.2f mm, p95 %.2f mm, max %.2f mm, "
              "%.1f s (before: mean %.2f mm)%s -> %s\n",
    options.seed, options.maxDisplacementMm, ours.mean, ours.p95, ours.max, runtime, before.mean,
    elastixLine.c_str(), options.out.c_str());
  std::fflush(stdout);
  if (options.requireMeanMm >= 0.0 && ours.mean > options.requireMeanMm)
  {
    char text[120];
    std::snprintf(text, sizeof(text), "the mean vertex error %.2f mm exceeds the required %.2f mm",
      ours.mean, options.requireMeanMm);
    throw Error(text);
  }
  if (options.requireP95Mm >= 0.0 && ours.p95 > options.requireP95Mm)
  {
    char text[120];
    std::snprintf(text, sizeof(text),
      "the 95th percentile vertex error %.2f mm exceeds the required %.2f mm", ours.p95,
      options.requireP95Mm);
    throw Error(text);
  }
}

} // namespace

void addEvaluateWarpCommand(CLI::App& evaluate)
{
  auto options = std::make_shared<EvaluateWarpOptions>();
  CLI::App* warp = evaluate.add_subcommand("warp",
    "P4: deform a CT by a known random smooth field, register the original to it, and report "
    "the per-vertex error of the warped airway mesh (and elastix's, when installed)");
  warp->add_option("--ct", options->ct, "CT volume: file or DICOM folder")->required();
  warp->add_option("--out", options->out, "Result file (.json)")->required();
  warp
    ->add_option("--max-displacement-mm", options->maxDisplacementMm,
      "Largest displacement of the known deformation over the airway (mm)")
    ->capture_default_str();
  warp->add_option("--seed", options->seed, "Seed of the deformation (the noise uses seed + 1000)")
    ->capture_default_str();
  warp->add_option("--noise-hu", options->noiseHU, "Standard deviation of the added noise (HU)")
    ->capture_default_str();
  warp
    ->add_option("--control-spacing-mm", options->controlSpacingMm,
      "Control point spacing of the known deformation (mm)")
    ->capture_default_str();
  warp->add_flag("--no-elastix", options->noElastix, "Do not run elastix even if it is installed");
  warp
    ->add_option("--elastix-parameters", options->elastixParameters,
      "Folder with the elastix parameter files affine.txt and bspline.txt")
    ->capture_default_str();
  warp->add_option("--require-mean-mm", options->requireMeanMm,
    "Fail (exit 1) when the mean vertex error exceeds this (mm)");
  warp->add_option("--require-p95-mm", options->requireP95Mm,
    "Fail (exit 1) when the 95th percentile vertex error exceeds this (mm)");
  warp->callback([options] { runEvaluateWarp(*options); });
}

} // namespace vimlop
