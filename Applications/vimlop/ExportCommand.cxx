#include "CommandLine.h"
#include "Commands.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Results/SlicerSceneExport.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>

namespace vimlop
{

namespace
{

struct ExportOptions
{
  std::string result;
  std::string out;
  std::string ct;
  bool noCT = false;
  std::string transformFormat = "tfm";
  bool force = false;
  bool json = false;
};

void runExport(const ExportOptions& o)
{
  if (o.noCT && !o.ct.empty())
  {
    throw Error("give --ct or --no-ct, not both");
  }
  SlicerSceneOptions options;
  options.transformExtension = "." + o.transformFormat;
  options.ctPath = o.ct;
  options.ctFromResult = !o.noCT;
  options.onProgress = [](const std::string& step)
  { std::fprintf(stderr, "export: %s\n", step.c_str()); };
  const SlicerSceneFiles files = exportResultForSlicer(o.result, o.out, o.force, options);
  CommandSummary summary;
  summary.lines.push_back(formatText("export: %s/Scene.mrml with %s%d camera poses "
                                     "(CameraToCT.seq.mha, Transforms/*.%s) and %zu files in all",
    o.out.c_str(), files.withCT ? "the CT, " : "no CT, ", files.frames, o.transformFormat.c_str(),
    files.files.size()));
  summary.json = { { "folder", o.out }, { "scene", files.files.front() },
    { "camera_poses", files.frames }, { "with_ct", files.withCT },
    { "transform_format", o.transformFormat }, { "files", files.files } };
  printSummary(summary, o.json);
}

} // namespace

void addExportCommand(CLI::App& app)
{
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command = app.add_subcommand("export",
    "Write a registration result for 3D Slicer and ITK: a Slicer scene (Scene.mrml) with the CT, "
    "the airway, the registered points and the camera moving along its path (a linear transform "
    "sequence), and every pose as an ITK transform file (Documentation/Exchange.md)");
  command->add_option("result", options->result, "result folder (written by vimlop register)")
    ->required();
  command->add_option("--out", options->out, "export folder (created; replaced only with --force)")
    ->required();
  command->add_option("--ct", options->ct,
    "CT to put in the scene as CT.nrrd (default: the CT the result names, if it is still there)");
  command->add_flag("--no-ct", options->noCT, "leave the CT out of the scene");
  command
    ->add_option("--transform-format", options->transformFormat,
      "ITK transform file format: tfm (text), h5 (HDF5) or mat (MATLAB, as ANTs writes)")
    ->capture_default_str()
    ->check(CLI::IsMember({ "tfm", "h5", "mat" }));
  command->add_flag("--force", options->force, "replace an earlier export in --out");
  addJsonFlag(*command, options->json);
  command->callback([options] { runExport(*options); });
}

} // namespace vimlop
