#include "CommandLine.h"
#include "Commands.h"

#include "TerminalProgress.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Evaluation/Peers/ElastixParameterFiles.h>
#include <vimlop/Evaluation/TemplateWarpProtocol.h>
#include <vimlop/Imaging/CTVolumeIO.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace vimlop
{

namespace
{

struct EvaluateWarpOptions
{
  std::string ct;
  std::string out;
  TemplateWarpProtocolOptions protocol;
  bool noElastix = false;
  std::string elastixParameters = defaultElastixParametersFolder();
  double requireMeanMm = -1.0;
  double requireP95Mm = -1.0;
  bool requireElastix = false;
  bool json = false;
};

void runEvaluateWarp(EvaluateWarpOptions options)
{
  namespace fs = std::filesystem;
  const fs::path outPath(options.out);
  TemplateWarpProtocolOptions& protocol = options.protocol;
  protocol.runElastix = !options.noElastix;
  protocol.elastixParametersFolder = options.elastixParameters;
  protocol.elastixWorkFolder =
    (outPath.parent_path() / (outPath.stem().string() + "-elastix")).string();
  protocol.validate();
  if (outPath.extension() != ".json")
  {
    throwFileError(options.out, "the result file must be .json");
  }
  const ProgressCallback terminal = terminalProgress("evaluate warp");
  const EvaluationProgress progress = [&](const std::string& step, int done, int total)
  {
    reportProgress(terminal, static_cast<double>(done) / total, step);
    return true;
  };

  const CTVolume ct = readCTVolume(options.ct);
  const TemplateWarpProtocolReport report = runTemplateWarpProtocol(ct, protocol, progress);
  for (const std::string& warning : report.warnings)
  {
    std::cerr << "vimlop evaluate warp: warning: " << warning << "\n";
  }
  nlohmann::json json = report.toJson();
  json["ct"] = options.ct;
  // Atomically: a cohort takes a result file that exists for a complete one.
  writeJsonFile(json, options.out);
  printSummary({ { "vimlop evaluate warp: " + report.summaryText() + " -> " + options.out }, json },
    options.json);
  std::fflush(stdout);
  report.requireErrorsAtMost(options.requireMeanMm, options.requireP95Mm);
  if (options.requireElastix)
  {
    report.requireNoWorseThanElastix();
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
    ->add_option("--max-displacement-mm", options->protocol.maxDisplacementMm,
      "Largest displacement of the known deformation over the airway (mm)")
    ->capture_default_str();
  warp
    ->add_option(
      "--seed", options->protocol.seed, "Seed of the deformation (the noise uses seed + 1000)")
    ->capture_default_str();
  warp
    ->add_option(
      "--noise-hu", options->protocol.noiseHU, "Standard deviation of the added noise (HU)")
    ->capture_default_str();
  warp
    ->add_option("--control-spacing-mm", options->protocol.controlSpacingMm,
      "Control point spacing of the known deformation (mm)")
    ->capture_default_str();
  PatientScanOptions& scan = options->protocol.scan;
  warp
    ->add_option("--patient-pixel-mm", scan.pixelSpacingMm,
      "In-plane voxel spacing of the patient's scan (mm; 0: the CT's)")
    ->capture_default_str();
  warp
    ->add_option("--patient-slice-mm", scan.sliceSpacingMm,
      "Slice spacing and thickness of the patient's scan (mm; 0: the CT's)")
    ->capture_default_str();
  warp
    ->add_option("--patient-blur-mm", scan.blurMm,
      "Extra Gaussian blur of the patient's scan, a softer kernel (sigma, mm)")
    ->capture_default_str();
  warp
    ->add_option("--patient-rotation-deg", scan.rotationDeg,
      "The patient's head turned in the scanner about the left-right axis (deg)")
    ->capture_default_str();
  warp->add_option_function<std::string>(
    "--patient-shift-mm",
    [&scan](const std::string& list)
    {
      const std::vector<double> shift = parseNumbers(list, "--patient-shift-mm");
      if (shift.size() != 3)
      {
        throw Error("--patient-shift-mm: '" + list + "' must be three numbers (x,y,z mm)");
      }
      scan.shiftMm = { shift[0], shift[1], shift[2] };
    },
    "The patient's head moved in the scanner (x,y,z mm)");
  AnatomyEditOptions& edits = options->protocol.edits;
  warp
    ->add_option("--edits", edits.count,
      "Local edits of the patient's anatomy (tissue grown, shrunk, air filled, in turn)")
    ->capture_default_str();
  warp
    ->add_option_function<std::string>(
      "--edit-sites",
      [&edits](const std::string& sites)
      {
        edits.placement = sites == "anatomical" ? AnatomyEditPlacement::AnatomicalSites
                                                : AnatomyEditPlacement::RandomWall;
      },
      "Where the edits go: random (points of the airway wall, default) or anatomical (a "
      "deviated septum, a larger inferior turbinate, a smaller middle turbinate, a filled "
      "maxillary sinus, in that order; at most 4)")
    ->check(CLI::IsMember({ "random", "anatomical" }));
  warp->add_option("--edit-radius-mm", edits.radiusMm, "Radius of each edit (mm)")
    ->capture_default_str();
  warp->add_option("--edit-depth-mm", edits.depthMm, "How far an edit grows or shrinks tissue (mm)")
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
  warp->add_flag("--require-no-worse-than-elastix", options->requireElastix,
    "Fail (exit 1) when the mean vertex error or the runtime exceeds elastix's in this run");
  addTemplateRegistrationOptions(*warp, options->protocol.registration);
  addJsonFlag(*warp, options->json);
  warp->callback([options] { runEvaluateWarp(*options); });
}

} // namespace vimlop
