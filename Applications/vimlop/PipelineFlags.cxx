#include "PipelineFlags.h"

#include "CommandLine.h"

#include <CLI/CLI.hpp>

#include <sstream>

namespace vimlop
{

namespace
{

std::string text(double value)
{
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string joined(const std::vector<double>& values)
{
  std::string list;
  for (double v : values)
  {
    list += (list.empty() ? "" : ",") + text(v);
  }
  return list;
}

} // namespace

void addPipelineOptions(CLI::App& c, VideoRegistrationPipeline::Options& p)
{
  RegistrationOptions& r = p.registration;
  c.add_option(
     "--point-noise-mm", p.pointNoiseFloorMm, "std added to every SfM point's covariance, mm")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c.add_option_function<double>(
     "--contour-variance-px2",
     [&r](double v) { r.contourMatch.positionCovariancePx2 = v * Eigen::Matrix2d::Identity(); },
     "contour position noise Σ2d, px² (paper: 1 for video)")
    ->default_str(text(r.contourMatch.positionCovariancePx2(0, 0)))
    ->check(CLI::PositiveNumber);
  c.add_option("--kappa", r.contourMatch.kappa, "contour orientation concentration κ (paper: 200)")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c.add_option("--trim", r.trimFraction, "initial trim ratio p_t of 3-D pairs")
    ->capture_default_str()
    ->check(CLI::Range(0.0, 0.9));
  c.add_option("--chi2-p", r.chiSquareProbability, "chi-square outlier test probability")
    ->capture_default_str()
    ->check(CLI::Range(0.5, 0.99999));
  c.add_option("--scale-bound", p.scaleBoundFactor,
     "scale bounds: the initial scale divided and multiplied by this")
    ->capture_default_str()
    ->check(CLI::Range(1.0001, 10.0));
  c.add_option("--max-iterations", r.maxIterations, "iteration cap per start")
    ->capture_default_str()
    ->check(CLI::Range(1, 100000));
  c.add_option("--threads", p.threads, "threads, 0 for all cores")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c.add_option("--screen-iterations", p.multiStart.screeningIterations,
     "canonical: iterations of every start before the finalists are chosen (0: all run fully)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c.add_option(
     "--finalists", p.multiStart.finalists, "canonical: starts run fully, at every scale factor")
    ->capture_default_str()
    ->check(CLI::Range(1, 100000));
  c.add_option_function<std::string>(
     "--scale-factors",
     [&p](const std::string& text)
     { p.multiStart.scaleFactors = parseNumbers(text, "--scale-factors"); },
     "canonical: variations of the initial scale per start")
    ->default_str(joined(p.multiStart.scaleFactors));
  c.add_option("--canonical-spacing-mm", p.canonical.spacingMm,
     "canonical: distance between generated canonical positions, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c.add_option("--failure-threshold-px", p.multiStart.failureContourErrorPx,
     "contour error above which the result is flagged as a failure, px (calibrated on P3)")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
}

} // namespace vimlop
