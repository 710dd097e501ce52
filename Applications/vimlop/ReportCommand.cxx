#include "Commands.h"

#include "CommandLine.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Rendering/OffscreenRendering.h>
#include <vimlop/Report/RegistrationReport.h>
#include <vimlop/Results/PerturbationRuns.h>
#include <vimlop/Results/RegistrationRecordIO.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace vimlop
{

namespace
{

struct ReportCommandOptions
{
  std::string result;
  std::string perturbation;
  std::string out;
  int maxOverlays = 0;
  std::string ct;
  bool noCtSlices = false;
  bool json = false;
};

void runReport(const ReportCommandOptions& o)
{
  if (o.result.empty() && o.perturbation.empty())
  {
    throw Error("give --result, --perturbation or both");
  }
  // Read everything before rendering anything, so bad input fails fast.
  std::optional<RegistrationRecord> record;
  if (!o.result.empty())
  {
    record = readRegistrationRecord(o.result);
  }
  std::vector<PerturbationRun> runs;
  if (!o.perturbation.empty())
  {
    runs = readPerturbationRuns(o.perturbation);
    if (runs.empty())
    {
      throwFileError(o.perturbation, "the perturbation study has no runs");
    }
  }
  requireOffscreenRendering("vimlop report");
  RegistrationReportOptions options;
  options.maxOverlayFrames = o.maxOverlays;
  options.ctPath = o.ct;
  options.ctSlices = !o.noCtSlices;
  const RegistrationReport report =
    RegistrationReport::write(record ? &*record : nullptr, o.result, runs, o.out, options);

  const std::string index = (std::filesystem::path(o.out) / "index.html").string();
  CommandSummary summary;
  std::string line =
    formatText("report: %zu pictures in %s", report.pictures.size(), index.c_str());
  if (record)
  {
    line += formatText("; contour error %.2f px before, %.2f px after", report.contourErrorBeforePx,
      report.contourErrorAfterPx);
    if (report.treAfterMm)
    {
      line +=
        formatText("; TRE %.3f mm before, %.3f mm after", *report.treBeforeMm, *report.treAfterMm);
    }
  }
  if (!runs.empty())
  {
    line += formatText("; %zu perturbation runs", runs.size());
  }
  summary.lines.push_back(line);
  if (report.verdict)
  {
    summary.lines.push_back("verdict: " + report.verdict->headline());
  }
  // The report's own numbers, as its report.json holds them.
  summary.json = nlohmann::json::parse(report.reportJson);
  summary.json["index"] = index;
  printSummary(summary, o.json);
}

} // namespace

void addReportCommand(CLI::App& app)
{
  auto options = std::make_shared<ReportCommandOptions>();
  CLI::App* report = app.add_subcommand("report",
    "Render the report of a registration result folder (the verdict, contour overlays before and "
    "after, errors per frame, 3-D scene and interactive view, the scope in the CT's slices, plots "
    "per iteration, the run) and/or of a perturbation study: index.html, report.json, PNGs");
  report->add_option("--result", options->result,
    "result folder (written by vimlop evaluate synthetic --save-trial or vimlop register)");
  report->add_option("--perturbation", options->perturbation,
    "perturbation study JSON with a \"runs\" list (offset_mm, offset_deg, final_error_mm, "
    "contour_error_px, success)");
  report->add_option("--out", options->out, "report folder (created if needed)")->required();
  report
    ->add_option("--max-overlays", options->maxOverlays,
      "draw overlays for at most this many frames, evenly spread (0: all)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  CLI::Option* ct = report->add_option("--ct", options->ct,
    "the CT to draw the scope's slices from (default: the CT the result names, when it is there)");
  report->add_flag("--no-ct-slices", options->noCtSlices, "no CT slices (e.g. a CT slow to read)")
    ->excludes(ct);
  addJsonFlag(*report, options->json);
  report->callback([options] { runReport(*options); });
}

} // namespace vimlop
