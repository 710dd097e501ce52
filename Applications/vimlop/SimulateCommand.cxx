#include "Commands.h"

#include "CommandLine.h"
#include "TerminalEvaluationProgress.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/EndoscopeSimulation.h>
#include <vimlop/Evaluation/SimulatedWorld.h>
#include <vimlop/Evaluation/WorldPreset.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <memory>
#include <vector>

namespace vimlop
{

namespace
{

struct SimulateOptions
{
  std::string mesh;
  std::string ct;
  std::string out;
  bool json = false;
  /// The world: its model errors and its video's (an ideal world by default).
  WorldSettings settings;
};

void runSimulate(SimulateOptions o)
{
  const auto start = std::chrono::steady_clock::now();
  PinholeCamera& k = o.settings.video.intrinsics;
  k.fy = k.fx; // square pixels, principal point at the centre
  k.cx = 0.5 * (k.widthPx - 1);
  k.cy = 0.5 * (k.heightPx - 1);
  // Before the display check: a wrong setting is reported wherever it runs.
  o.settings.video.validate();
  // The truth is what the endoscope sees and where its path runs; a user
  // gets the model (model.vtp), never the truth.
  const SimulatedWorld world =
    loadSimulatedWorld(o.mesh, o.ct, o.settings.model, "vimlop simulate");
  const RegistrationModel model = makeEmbreeRegistrationModel(world.truth);
  const SimulatedVideo video =
    simulateEndoscopeVideo(model, o.settings.video, terminalEvaluationProgress());
  writeSimulatedVideo(video, o.out);
  writeSimulatedWorld(world, o.out);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double pathMm = video.pathLengthMm();
  const double wallMm = video.leastWallDistanceMm(model);
  CommandSummary summary;
  summary.lines.push_back(
    formatText("simulated %d frames of %dx%d px along a %.1f mm path (least wall distance %.2f "
               "mm) in %.1f s; wrote '%s'",
      o.settings.video.frames, k.widthPx, k.heightPx, pathMm, wallMm, seconds, o.out.c_str()));
  summary.json = { { "frames", o.settings.video.frames }, { "width_px", k.widthPx },
    { "height_px", k.heightPx }, { "path_length_mm", pathMm }, { "least_wall_distance_mm", wallMm },
    { "seconds", seconds }, { "out", o.out } };
  printSummary(summary, o.json);
}

} // namespace

void addSimulateCommand(CLI::App& app)
{
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* simulate = app.add_subcommand("simulate",
    "Simulate an endoscope sequence in the airway: frames, depth maps, intrinsics, true poses, "
    "tracker CSV");
  addModelOptions(*simulate, o->mesh, o->ct);
  simulate->add_option("--out", o->out, "output folder")->required();
  simulate->add_option("--frames", o->settings.video.frames, "number of frames")
    ->capture_default_str()
    ->check(CLI::Range(2, 10000));
  simulate->add_option("--seed", o->settings.video.seed, "random seed (path, texture, noise)")
    ->capture_default_str();
  PinholeCamera& k = o->settings.video.intrinsics;
  simulate->add_option("--width", k.widthPx, "image width, pixels")
    ->capture_default_str()
    ->check(CLI::Range(16, 8192));
  simulate->add_option("--height", k.heightPx, "image height, pixels")
    ->capture_default_str()
    ->check(CLI::Range(16, 8192));
  simulate->add_option("--focal", k.fx, "focal length, pixels (principal point at the centre)")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  simulate
    ->add_option("--clearance-mm", o->settings.video.trajectory.minClearanceMm,
      "least distance of the optical centre to the wall, mm")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  simulate
    ->add_option("--upright-deg", o->settings.video.trajectory.uprightRollDeg,
      "keep the image up within this many degrees of superior (negative: any roll)")
    ->capture_default_str()
    ->check(CLI::Range(-1.0, 180.0));
  simulate->add_option("--noise", o->settings.video.noiseSigma, "picture noise std, grey levels")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  simulate->add_option("--blur-px", o->settings.video.blurSigmaPx, "picture blur std, pixels")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);

  addWorldPresetOption(*simulate, o->settings);
  addSimulationOptions(*simulate, o->settings.video);
  addWorldOptions(*simulate, o->settings.model);
  addJsonFlag(*simulate, o->json);
  simulate->callback([o] { runSimulate(*o); });
}

} // namespace vimlop
