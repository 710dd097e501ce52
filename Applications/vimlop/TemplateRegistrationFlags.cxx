#include "CommandLine.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/TemplateRegistration.h>

#include <CLI/CLI.hpp>

#include <cmath>

namespace vimlop
{

namespace
{

/// "20,10" as iteration counts; `what` names the option in errors.
std::vector<int> parseCounts(const std::string& text, const std::string& what)
{
  std::vector<int> counts;
  for (double n : parseNumbers(text, what))
  {
    if (!(n >= 0.0 && n == std::floor(n) && n < 1e6))
    {
      throw Error(what + ": '" + text + "' must list whole numbers of iterations, 0 or more");
    }
    counts.push_back(static_cast<int>(n));
  }
  return counts;
}

std::string joinCounts(const std::vector<int>& counts)
{
  return joinNumbers(std::vector<double>(counts.begin(), counts.end()));
}

} // namespace

void addTemplateRegistrationOptions(CLI::App& c, TemplateRegistrationOptions& r)
{
  c.add_option(
     "--margin-mm", r.marginMm, "margin added on every side of the registered region (mm)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c.add_option_function<std::string>(
     "--affine-levels-mm",
     [&r](const std::string& list)
     { r.affineLevelSpacingMm = parseNumbers(list, "--affine-levels-mm"); },
     "affine stage: voxel size of each level, coarse to fine (mm)")
    ->default_str(joinNumbers(r.affineLevelSpacingMm));
  c.add_option_function<std::string>(
     "--affine-iterations",
     [&r](const std::string& list)
     { r.affineIterations = parseCounts(list, "--affine-iterations"); },
     "affine stage: iterations of each level")
    ->default_str(joinCounts(r.affineIterations));
  c.add_option("--histogram-bins", r.histogramBins,
     "bins of Mattes mutual information (affine stage; SyN with --syn-metric mi)")
    ->capture_default_str()
    ->check(CLI::Range(4, 1024));
  c.add_option_function<std::string>(
     "--bspline-grid-mm",
     [&r](const std::string& list)
     {
       r.bsplineGridMm =
         list == "none" ? std::vector<double>{} : parseNumbers(list, "--bspline-grid-mm");
     },
     "B-spline stage: control point spacing of each level, coarse to fine (mm; none: no stage)")
    ->default_str(joinNumbers(r.bsplineGridMm));
  c.add_option_function<std::string>(
     "--bspline-levels-mm",
     [&r](const std::string& list)
     { r.bsplineLevelSpacingMm = parseNumbers(list, "--bspline-levels-mm"); },
     "B-spline stage: voxel size of each level (mm)")
    ->default_str(joinNumbers(r.bsplineLevelSpacingMm));
  c.add_option_function<std::string>(
     "--bspline-iterations",
     [&r](const std::string& list)
     { r.bsplineIterations = parseCounts(list, "--bspline-iterations"); },
     "B-spline stage: L-BFGS function evaluations of each level, at most")
    ->default_str(joinCounts(r.bsplineIterations));
  c.add_option("--bspline-sampling", r.bsplineSamplingFraction,
     "B-spline stage: fraction of each level's voxels the metric samples")
    ->capture_default_str()
    ->check(CLI::Range(1e-4, 1.0));
  c.add_option("--bspline-bending", r.bsplineBendingWeightMm2,
     "B-spline stage: weight of the bending energy (mm^2)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c.add_option_function<std::string>(
     "--syn-metric",
     [&r](const std::string& name) { r.metric = templateRegistrationMetricFromName(name); },
     "SyN stage: similarity, mi (Mattes mutual information), ms (mean squares) or cc (ANTs' "
     "neighbourhood cross-correlation)")
    ->check(CLI::IsMember({ "mi", "ms", "cc" }))
    ->default_str(templateRegistrationMetricName(r.metric));
  c.add_option("--cc-radius", r.correlationRadiusVoxels,
     "SyN stage with --syn-metric cc: neighbourhood radius (voxels of the level)")
    ->capture_default_str()
    ->check(CLI::Range(1, 16));
  c.add_option_function<std::string>(
     "--syn-levels-mm",
     [&r](const std::string& list) { r.synLevelSpacingMm = parseNumbers(list, "--syn-levels-mm"); },
     "SyN stage: voxel size of each level, coarse to fine (mm)")
    ->default_str(joinNumbers(r.synLevelSpacingMm));
  c.add_option_function<std::string>(
     "--syn-iterations",
     [&r](const std::string& list) { r.synIterations = parseCounts(list, "--syn-iterations"); },
     "SyN stage: iterations of each level")
    ->default_str(joinCounts(r.synIterations));
  c.add_option("--syn-learning-rate", r.synLearningRate,
     "SyN stage: largest update per iteration (voxels of the level)")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c.add_option("--update-field-variance", r.updateFieldVariance,
     "SyN stage: Gaussian smoothing of each update field (voxels^2 of the level)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c.add_option("--total-field-variance", r.totalFieldVariance,
     "SyN stage: Gaussian smoothing of the total field after each update (voxels^2; 0: none)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
}

} // namespace vimlop
