#include "Commands.h"

#include "CommandLine.h"
#include "TerminalEvaluationProgress.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/PerturbationProtocol.h>
#include <vimlop/Evaluation/SimulatedWorld.h>
#include <vimlop/Evaluation/SyntheticDataSurface.h>
#include <vimlop/Evaluation/SyntheticProtocol.h>
#include <vimlop/Evaluation/TrackingProtocol.h>
#include <vimlop/Evaluation/VideoProtocol.h>
#include <vimlop/Evaluation/WorldPreset.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/ModelLoading.h>
#include <vimlop/Rendering/OffscreenRendering.h>
#include <vimlop/Report/RegistrationReport.h>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>

namespace vimlop
{

namespace
{

// Each command's options are the protocol's; the ranges and lists are text
// (shown with the protocol's defaults) parsed when the command runs.
struct SyntheticCommand
{
  std::string mesh, ct, out;
  SyntheticProtocolOptions protocol;
  std::string methods = joinList(protocol.methods);
  std::string misalignMm =
    joinNumbers({ protocol.synthetic.misalignMinMm, protocol.synthetic.misalignMaxMm });
  std::string misalignDeg =
    joinNumbers({ protocol.synthetic.misalignMinDeg, protocol.synthetic.misalignMaxDeg });
  std::string dataSurface = "model";
  bool json = false;
};

/// P1's model and the surface its data are drawn from (the model by default).
TriangleMesh syntheticModel(const SyntheticCommand& c, SyntheticProtocolOptions& options)
{
  if (options.dataSurfaceMaking.surface == SyntheticDataSurface::Model)
  {
    return airwayMeshFrom(c.mesh, c.ct);
  }
  if (c.mesh.empty() == c.ct.empty())
  {
    throw Error("give exactly one of --mesh and --ct");
  }
  const SyntheticSurfaces surfaces = c.ct.empty()
    ? makeSyntheticSurfaces(loadAirwayMesh(c.mesh), options.dataSurfaceMaking)
    : makeSyntheticSurfaces(
        readCTVolume(c.ct), options.dataSurfaceMaking, terminalEvaluationProgress());
  options.dataSurface = surfaces.data;
  return surfaces.model;
}

void runSynthetic(SyntheticCommand c)
{
  SyntheticProtocolOptions& options = c.protocol;
  if (!options.saveTrialFolder.empty())
  {
    requireOffscreenRendering("--save-trial");
  }
  options.methods = parseList(c.methods, "--methods");
  checkSyntheticProtocolMethods(options.methods);
  std::tie(options.synthetic.misalignMinMm, options.synthetic.misalignMaxMm) =
    parseRange(c.misalignMm, "--misalign-mm");
  std::tie(options.synthetic.misalignMinDeg, options.synthetic.misalignMaxDeg) =
    parseRange(c.misalignDeg, "--misalign-deg");
  options.dataSurfaceMaking.surface = syntheticDataSurfaceFromString(c.dataSurface);
  // Before the CT is read: a wrong setting is reported at once.
  validateSyntheticProtocolOptions(options);
  const TriangleMesh mesh = syntheticModel(c, options);
  const SyntheticProtocolReport report =
    runSyntheticProtocol(mesh, options, terminalEvaluationProgress());
  writeJsonFile(report.toJson(), c.out);
  printSummary({ report.summaryLines(), report.toJson() }, c.json);
}

struct VideoCommand
{
  std::string mesh, ct, out;
  VideoProtocolOptions protocol;
  /// The world; its video settings become the protocol's simulation.
  WorldSettings world;
  std::string perturbMm = joinNumbers({ protocol.perturbMinMm, protocol.perturbMaxMm });
  std::string perturbDeg = joinNumbers({ protocol.perturbMinDeg, protocol.perturbMaxDeg });
  bool json = false;
};

void runVideo(VideoCommand c)
{
  VideoProtocolOptions& options = c.protocol;
  if (options.workFolder.empty())
  {
    options.workFolder = c.out + ".work";
  }
  std::tie(options.perturbMinMm, options.perturbMaxMm) = parseRange(c.perturbMm, "--perturb-mm");
  std::tie(options.perturbMinDeg, options.perturbMaxDeg) =
    parseRange(c.perturbDeg, "--perturb-deg");
  options.simulation = c.world.video;
  options.validate();
  options.simulation.validate();
  const SimulatedWorld world =
    loadSimulatedWorld(c.mesh, c.ct, c.world.model, "vimlop evaluate video");
  const VideoProtocolReport report = runVideoProtocol(world, options, terminalEvaluationProgress());
  writeJsonFile(report.toJson(), c.out);
  printSummary({ report.summaryLines(), report.toJson() }, c.json);
}

struct TrackingCommand
{
  std::string mesh, ct, out;
  TrackingProtocolOptions protocol;
  /// The world; its video settings (600 frames along a 48-pose path by
  /// default) become the protocol's sequence.
  WorldSettings world = []
  {
    WorldSettings w;
    w.video = TrackingProtocolOptions::defaultSimulation();
    return w;
  }();
  bool json = false;
};

void runTracking(TrackingCommand c)
{
  TrackingProtocolOptions& options = c.protocol;
  options.simulation = c.world.video;
  options.simulation.replay.leadFrames = options.registrationFrames;
  if (options.registration.workFolder.empty())
  {
    options.registration.workFolder = c.out + ".work";
  }
  options.validate();
  const SimulatedWorld world =
    loadSimulatedWorld(c.mesh, c.ct, c.world.model, "vimlop evaluate tracking");
  const TrackingProtocolReport report =
    runTrackingProtocol(world, options, terminalEvaluationProgress());
  writeJsonFile(report.toJson(), c.out);
  printSummary({ report.summaryLines(), report.toJson() }, c.json);
}

struct PerturbationCommand
{
  std::string mesh, ct, out;
  PerturbationProtocolOptions protocol;
  std::string offsets = joinNumbers(protocol.offsets);
  bool noReport = false;
  bool json = false;
};

void runPerturbation(PerturbationCommand c)
{
  PerturbationProtocolOptions& options = c.protocol;
  options.offsets = parseNumbers(c.offsets, "--offsets-mm");
  options.validate();
  requireOffscreenRendering("vimlop evaluate perturbation");
  const TriangleMesh mesh = airwayMeshFrom(c.mesh, c.ct);
  std::filesystem::create_directories(c.out);
  const PerturbationProtocolReport p3 =
    runPerturbationProtocol(mesh, options, terminalEvaluationProgress());
  namespace fs = std::filesystem;
  writePerturbationRuns(p3.runs, (fs::path(c.out) / "runs.json").string());
  if (!c.noReport)
  {
    RegistrationReport::write(
      nullptr, "", p3.runs, (fs::path(c.out) / "report").string(), RegistrationReportOptions());
  }
  writeJsonFile(p3.toJson(), (fs::path(c.out) / "p3.json").string());
  printSummary({ p3.summaryLines(), p3.toJson() }, c.json);
}

} // namespace

CLI::App* addEvaluateCommand(CLI::App& app)
{
  CLI::App* evaluate = app.add_subcommand(
    "evaluate", "Run an evaluation protocol (DESIGN section 6); results go to a JSON file");
  evaluate->require_subcommand(1);

  auto synthetic = std::make_shared<SyntheticCommand>();
  SyntheticProtocolOptions& p1Options = synthetic->protocol;
  CLI::App* p1 = evaluate->add_subcommand("synthetic",
    "P1, the paper's synthetic experiment: 6 cameras, 900 noisy points, contours, misaligned data; "
    "TRE of V-IMLOP, its baselines and Open3D peers");
  addModelOptions(*p1, synthetic->mesh, synthetic->ct);
  p1->add_option("--out", synthetic->out, "result JSON file")->required();
  p1->add_option("--trials", p1Options.trials, "number of trials")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  p1->add_option("--seed", p1Options.seed, "random seed")->capture_default_str();
  p1->add_option(
      "--misalign-mm", synthetic->misalignMm, "range of the initial translation error, mm")
    ->capture_default_str();
  p1->add_option(
      "--misalign-deg", synthetic->misalignDeg, "range of the initial rotation error, degrees")
    ->capture_default_str();
  p1->add_option("--points", p1Options.synthetic.points,
      "SfM points per trial (the paper's 900; more compares the methods' speed at scale)")
    ->capture_default_str()
    ->check(CLI::Range(3, 10000000));
  p1->add_option("--contour-noise-px", p1Options.synthetic.contourNoisePx,
      "noise added to the video contour points, std per axis, px (the paper's Σ2d = 9 px²: 3)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  p1->add_option("--contour-noise-kappa", p1Options.synthetic.contourNormalKappa,
      "concentration of the noise on contour normals (the paper's 200; 0: none)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  // P1 faithful to a wrong model (issue 14): no range checks here, so that
  // the library's validation names the bad value in one message.
  p1->add_option("--data-surface", synthetic->dataSurface,
      "draw the points and contours from another surface than the model: model, finer (the "
      "CT's undecimated iso-surface), threshold (the CT segmented at --data-offset-hu) or "
      "deformed (the model through a smooth field of --data-deformation-mm)")
    ->capture_default_str()
    ->check(CLI::IsMember({ "model", "finer", "threshold", "deformed" }));
  p1->add_option("--data-offset-hu", p1Options.dataSurfaceMaking.offsetHU,
      "with --data-surface threshold: the data's air threshold minus the model's, HU")
    ->capture_default_str();
  p1->add_option("--data-deformation-mm", p1Options.dataSurfaceMaking.deformationMm,
      "with --data-surface deformed: the field's largest displacement, mm")
    ->capture_default_str();
  p1->add_option("--assumed-noise-scale", p1Options.assumedNoiseScale,
      "misspecified noise: the registration's noise model (point covariances, contour variance) "
      "is this times the true one")
    ->capture_default_str();
  p1->add_flag("--robust-contour-inflation", p1Options.robustContourInflation,
    "V8: inflate V-IMLOP's contour tests by the median match error, not the mean");
  p1->add_option("--start-scale-error", p1Options.synthetic.startScaleError,
      "wrong start scale: the registration starts from (1 + this) times the true scale")
    ->capture_default_str();
  p1->add_option("--methods", synthetic->methods,
      std::string("comma-separated methods: ") + syntheticProtocolMethodNames())
    ->capture_default_str();
  p1->add_option("--threads", p1Options.threads, "threads per registration, 0 for all cores")
    ->capture_default_str();
  p1->add_option("--save-trial", p1Options.saveTrialFolder,
    "also write trial 0 and its registration (by the first of vimlop, imlp, trimmed-icp in "
    "--methods) as a result folder for vimlop report, with the model rendered from the true "
    "cameras as frame pictures");
  addJsonFlag(*p1, synthetic->json);
  p1->callback([synthetic] { runSynthetic(*synthetic); });

  auto video = std::make_shared<VideoCommand>();
  VideoProtocolOptions& p2Options = video->protocol;
  CLI::App* p2 = evaluate->add_subcommand("video",
    "P2, the paper's simulated-video experiment: a virtual endoscope sequence, contour detection, "
    "SfM, tracker scale, a perturbed start; camera errors of V-IMLOP and IMLP");
  addModelOptions(*p2, video->mesh, video->ct);
  p2->add_option("--out", video->out, "result JSON file")->required();
  p2->add_option("--frames", video->world.video.frames, "frames of the sequence")
    ->capture_default_str()
    ->check(CLI::Range(3, 1000));
  p2->add_option("--seed", video->world.video.seed, "random seed (path, texture, noise, start)")
    ->capture_default_str();
  p2->add_option("--sfm", p2Options.sfm, "structure from motion: builtin or colmap")
    ->capture_default_str();
  p2->add_option(
      "--colmap", p2Options.colmapExecutable, "the COLMAP executable (with --sfm colmap)")
    ->capture_default_str();
  p2->add_option("--work", p2Options.workFolder, "folder for COLMAP's work (default: OUT.work)");
  p2->add_option("--perturb-mm", video->perturbMm, "range of the initial translation error, mm")
    ->capture_default_str();
  p2->add_option("--perturb-deg", video->perturbDeg, "range of the initial rotation error, degrees")
    ->capture_default_str();
  p2->add_option("--init", p2Options.init,
      "start: perturbed (the truth moved by --perturb-mm/--perturb-deg) or canonical "
      "(multi-start from canonical poses)")
    ->capture_default_str();
  p2->add_option("--upright-deg", p2Options.uprightRollDeg,
      "with --init canonical: the simulated scope's image up stays this close to superior, deg")
    ->capture_default_str()
    ->check(CLI::Range(0.0, 180.0));
  addWorldPresetOption(*p2, video->world);
  addSimulationOptions(*p2, video->world.video);
  addWorldOptions(*p2, video->world.model);
  addPipelineOptions(*p2, p2Options.pipeline);
  addJsonFlag(*p2, video->json);
  p2->callback([video] { runVideo(*video); });

  auto tracking = std::make_shared<TrackingCommand>();
  TrackingProtocolOptions& trackingOptions = tracking->protocol;
  CLI::App* track = evaluate->add_subcommand("tracking",
    "Tracking (issue 16): a long simulated sequence (forward and back, pauses, fast moves), its "
    "first frames registered by the main job, the rest tracked frame by frame; camera errors, "
    "drift, latency, frames tracked");
  addModelOptions(*track, tracking->mesh, tracking->ct);
  track->add_option("--out", tracking->out, "result JSON file")->required();
  track->add_option("--frames", tracking->world.video.frames, "frames of the sequence")
    ->capture_default_str()
    ->check(CLI::Range(4, 100000));
  track
    ->add_option("--path-frames", tracking->world.video.replay.pathFrames,
      "poses of the path the sequence plays along (forward and back)")
    ->capture_default_str()
    ->check(CLI::Range(2, 10000));
  track
    ->add_option("--seed", tracking->world.video.seed, "random seed (path, texture, noise, start)")
    ->capture_default_str();
  track
    ->add_option("--registration-frames", trackingOptions.registrationFrames,
      "frames registered by the main job before tracking")
    ->capture_default_str();
  addEndoscopeTrackerOptions(*track, trackingOptions.tracker, trackingOptions.trackerLag);
  track->add_flag("--tracker-prior", trackingOptions.trackerPrior,
    "give the tracker the simulated electromagnetic tracker's tip at each frame (the prediction "
    "after a lost frame, and frames farther from it than 3 mm degraded); with --tracker-rotation, "
    "its rotation too (frames turned from it by more than 5 degrees degraded)");
  addTrackingRefinementOptions(*track, trackingOptions.refineAgainstCT, trackingOptions.refinement);
  addTrackingRelocalisationOptions(
    *track, trackingOptions.relocalise, trackingOptions.relocalisation);
  addWorldPresetOption(*track, tracking->world);
  addSimulationOptions(*track, tracking->world.video);
  addWorldOptions(*track, tracking->world.model);
  addPipelineOptions(*track, trackingOptions.registration.pipeline);
  addJsonFlag(*track, tracking->json);
  track->callback([tracking] { runTracking(*tracking); });

  auto perturbation = std::make_shared<PerturbationCommand>();
  PerturbationProtocolOptions& p3Options = perturbation->protocol;
  CLI::App* p3 = evaluate->add_subcommand("perturbation",
    "P3: robustness to the initial pose on a simulated sequence; OUT/p3.json, OUT/runs.json and "
    "the Fig. 3 report in OUT/report");
  addModelOptions(*p3, perturbation->mesh, perturbation->ct);
  p3->add_option("--out", perturbation->out, "output folder")->required();
  p3->add_option("--offsets-mm", perturbation->offsets,
      "offsets of the start, each both mm of translation and degrees of rotation")
    ->capture_default_str();
  p3->add_option("--trials-per-offset", p3Options.trialsPerOffset, "registrations per offset")
    ->capture_default_str()
    ->check(CLI::Range(1, 10000));
  p3->add_option("--seed", p3Options.video.simulation.seed, "random seed (sequence and starts)")
    ->capture_default_str();
  p3->add_option("--frames", p3Options.video.simulation.frames, "frames of the sequence")
    ->capture_default_str()
    ->check(CLI::Range(2, 1000));
  p3->add_option("--success-mm", p3Options.successMm,
      "a run succeeds when its mean camera position error is at most this, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  p3->add_option("--threads", p3Options.video.pipeline.registration.threads,
      "threads over runs, 0 for all cores")
    ->capture_default_str();
  p3->add_flag("--no-report", perturbation->noReport, "skip the rendered report");
  addJsonFlag(*p3, perturbation->json);
  p3->callback([perturbation] { runPerturbation(*perturbation); });
  return evaluate;
}

} // namespace vimlop
