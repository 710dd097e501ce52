#include "CommandLine.h"
#include "Commands.h"

#include "TerminalProgress.h"
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/TemplateWarpJob.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

namespace vimlop
{

namespace
{

void runWarp(const TemplateWarpJobOptions& options, bool json)
{
  const TemplateWarpJobReport report = runTemplateWarpJob(options, terminalProgress("warp"),
    [](const std::string& warning) { std::cerr << "vimlop warp: warning: " << warning << "\n"; });
  const TemplateRegistration& r = report.registration;
  CommandSummary summary;
  summary.lines.push_back(
    formatText("vimlop warp: %zu meshes, %zu poses to the patient; correlation %.3f -> %.3f "
               "(affine) -> %.3f (deformable), %.1f s -> %s",
      report.meshCount, report.poseCount, r.initialCorrelation, r.affineCorrelation,
      r.finalCorrelation, report.totalSeconds, options.outputFolder.c_str()));
  // What registration.json holds, and where it and the other files are.
  summary.json = report.toJson();
  summary.json["out"] = options.outputFolder;
  printSummary(summary, json);
}

} // namespace

void addWarpCommand(CLI::App& app)
{
  auto options = std::make_shared<TemplateWarpJobOptions>();
  auto json = std::make_shared<bool>(false);
  CLI::App* warp = app.add_subcommand("warp",
    "Register a template CT to a patient CT (affine + SyN) and carry template meshes and camera "
    "poses into the patient");
  warp->add_option("--template-ct", options->templateCTPath, "Template CT: file or DICOM folder")
    ->required();
  warp->add_option("--patient-ct", options->patientCTPath, "Patient CT: file or DICOM folder")
    ->required();
  warp->add_option("--template-mesh", options->templateMeshPaths,
    "Mesh(es) in the template CT frame; default: the template's airway, segmented");
  warp->add_option("--template-poses", options->templatePosesPath,
    "Camera poses in the template CT frame (JSON, see Modules/Imaging/FramePoseIO.h)");
  warp
    ->add_option("--out", options->outputFolder,
      "Output folder: warped meshes (.vtp), poses.json, displacement fields, registration.json")
    ->required();
  addTemplateRegistrationOptions(*warp, options->registration);
  addJsonFlag(*warp, *json);
  warp->callback([options, json] { runWarp(*options, *json); });
}

} // namespace vimlop
