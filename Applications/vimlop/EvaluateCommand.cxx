#include "EvaluateCommand.h"

#include "CommandLine.h"
#include "TerminalEvaluationProgress.h"
#include <vimlop/Evaluation/PerturbationProtocol.h>
#include <vimlop/Evaluation/SyntheticProtocol.h>
#include <vimlop/Evaluation/VideoProtocol.h>
#include <vimlop/Imaging/ModelLoading.h>
#include <vimlop/Rendering/OffscreenRendering.h>
#include <vimlop/Report/RegistrationReport.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace vimlop
{

namespace
{

struct SyntheticCommandOptions
{
  std::string mesh;
  std::string ct;
  std::string out;
  int trials = 100;
  std::uint64_t seed = 1;
  std::string misalignMm = "2,3";
  std::string misalignDeg = "2,3";
  std::string methods = "vimlop,imlp,trimmed-icp,open3d-icp,open3d-gicp";
  int threads = 0;
  std::string saveTrial;
};

void runSynthetic(const SyntheticCommandOptions& o)
{
  SyntheticProtocolOptions options;
  options.trials = o.trials;
  options.seed = o.seed;
  options.threads = o.threads;
  options.saveTrialFolder = o.saveTrial;
  if (!o.saveTrial.empty())
  {
    requireOffscreenRendering("--save-trial");
  }
  options.methods = parseList(o.methods, "--methods");
  checkSyntheticProtocolMethods(options.methods);
  std::tie(options.synthetic.misalignMinMm, options.synthetic.misalignMaxMm) =
    parseRange(o.misalignMm, "--misalign-mm");
  std::tie(options.synthetic.misalignMinDeg, options.synthetic.misalignMaxDeg) =
    parseRange(o.misalignDeg, "--misalign-deg");
  const TriangleMesh mesh = airwayMeshFrom(o.mesh, o.ct);
  const SyntheticProtocolReport report =
    runSyntheticProtocol(mesh, options, terminalEvaluationProgress());
  writeJsonFile(report.toJson(), o.out);
  for (const SyntheticProtocolMethodReport& m : report.methods)
  {
    std::printf("P1 %-12s TRE median %.3f mm (mean %.3f, p95 %.3f), success %.0f %%, camera %.3f "
                "mm / %.3f deg, "
                "runtime median %.3f s\n",
      m.method.c_str(), m.treMedianMm, m.treMeanMm, m.treP95Mm, 100.0 * m.successRate,
      m.cameraPositionMedianMm, m.cameraAngleMedianDeg, m.runtimeMedianS);
  }
}

struct VideoCommandOptions
{
  std::string mesh;
  std::string ct;
  std::string out;
  int frames = 30;
  std::uint64_t seed = 1;
  std::string sfm = "builtin";
  std::string colmap = "colmap";
  std::string work;
  std::string perturbMm = "2,3";
  std::string perturbDeg = "2,3";
  int threads = 0;
  std::string init = "perturbed";
  double uprightDeg = 10.0;
  double canonicalSpacingMm = CanonicalPoseOptions().spacingMm;
  std::string scaleFactors = "0.9,1,1.1";
  int screeningIterations = MultiStartOptions().screeningIterations;
  int finalists = MultiStartOptions().finalists;
  double failureThresholdPx = MultiStartOptions().failureContourErrorPx;
};

void runVideo(const VideoCommandOptions& o)
{
  VideoProtocolOptions options;
  options.simulation.frames = o.frames;
  options.simulation.seed = o.seed;
  options.sfm = o.sfm;
  options.colmapExecutable = o.colmap;
  options.workFolder = o.work;
  if (options.workFolder.empty())
  {
    options.workFolder = o.out + ".work";
  }
  std::tie(options.perturbMinMm, options.perturbMaxMm) = parseRange(o.perturbMm, "--perturb-mm");
  std::tie(options.perturbMinDeg, options.perturbMaxDeg) =
    parseRange(o.perturbDeg, "--perturb-deg");
  options.init = o.init;
  options.uprightRollDeg = o.uprightDeg;
  VideoRegistrationPipeline::Options& pipeline = options.pipeline;
  pipeline.threads = o.threads;
  pipeline.canonical.spacingMm = o.canonicalSpacingMm;
  pipeline.multiStart.scaleFactors = parseNumbers(o.scaleFactors, "--scale-factors");
  pipeline.multiStart.screeningIterations = o.screeningIterations;
  pipeline.multiStart.finalists = o.finalists;
  pipeline.multiStart.failureContourErrorPx = o.failureThresholdPx;
  options.validate();
  requireOffscreenRendering("vimlop evaluate video");
  const TriangleMesh mesh = airwayMeshFrom(o.mesh, o.ct);
  const VideoProtocolReport report = runVideoProtocol(mesh, options, terminalEvaluationProgress());
  writeJsonFile(report.toJson(), o.out);
  const ContourScores& c = report.contours;
  std::printf(
    "P2 contours: precision %.3f, recall %.3f, median normal error %.1f deg; SfM (%s) %d points\n",
    c.precision, c.recall, c.normalErrorDegMedian, o.sfm.c_str(),
    static_cast<int>(report.sfmPoints));
  for (const VideoProtocolMethodReport& m : report.methods)
  {
    const VideoCameraErrors& e = m.errors;
    std::printf("P2 %-6s camera %.3f mm (max %.3f) / %.3f deg (max %.3f), scale error %.2f %%, "
                "runtime %.1f s\n",
      m.method.c_str(), e.positionMeanMm, e.positionMaxMm, e.angleMeanDeg, e.angleMaxDeg,
      100.0 * e.scaleErrorRel, e.runtimeS);
    if (m.multiStart)
    {
      std::printf("P2 %-6s multi-start of %d candidates: contour error %.2f px, %s\n",
        m.method.c_str(), static_cast<int>(report.candidates.value_or(0)),
        m.multiStart->contourErrorPx,
        m.multiStart->failureFlag ? "FLAGGED as a failure" : "not flagged");
    }
  }
}

struct PerturbationCommandOptions
{
  std::string mesh;
  std::string ct;
  std::string out;
  std::string offsets = "0,2,4,6,8,10";
  int trialsPerOffset = 10;
  std::uint64_t seed = 1;
  int frames = 30;
  double successMm = 1.0;
  int threads = 0;
  bool noReport = false;
};

void runPerturbation(const PerturbationCommandOptions& o)
{
  PerturbationProtocolOptions options;
  options.offsets = parseNumbers(o.offsets, "--offsets-mm");
  options.trialsPerOffset = o.trialsPerOffset;
  options.successMm = o.successMm;
  options.video.simulation.seed = o.seed;
  options.video.simulation.frames = o.frames;
  options.video.pipeline.threads = o.threads;
  options.validate();
  requireOffscreenRendering("vimlop evaluate perturbation");
  const TriangleMesh mesh = airwayMeshFrom(o.mesh, o.ct);
  std::filesystem::create_directories(o.out);
  const PerturbationProtocolReport p3 =
    runPerturbationProtocol(mesh, options, terminalEvaluationProgress());
  namespace fs = std::filesystem;
  writePerturbationRuns(p3.runs, (fs::path(o.out) / "runs.json").string());
  if (!o.noReport)
  {
    RegistrationReport::write(
      nullptr, "", p3.runs, (fs::path(o.out) / "report").string(), RegistrationReportOptions());
  }
  writeJsonFile(p3.toJson(), (fs::path(o.out) / "p3.json").string());
  for (const PerturbationOffsetReport& offset : p3.offsets)
  {
    std::printf("P3 offset %4.1f mm / %4.1f deg: success %3.0f %%, camera error median %.3f mm, "
                "contour error median %.2f px\n",
      offset.offsetMm, offset.offsetDeg, 100.0 * offset.successRate, offset.cameraPositionMedianMm,
      offset.contourErrorMedianPx);
  }
  if (!p3.auc)
  {
    std::printf("P3 %s; no ROC area (it needs both successes and failures)\n",
      p3.failures == 0 ? "every run succeeded" : "every run failed");
  }
  else
  {
    std::printf("P3 contour error separates failures from successes: ROC AUC %.3f, best "
                "threshold %.2f px (%d failures of %d runs)\n",
      *p3.auc, p3.failureThresholdPx.value_or(0.0), static_cast<int>(p3.failures), p3.runsTotal);
  }
}

} // namespace

CLI::App* addEvaluateCommand(CLI::App& app)
{
  CLI::App* evaluate = app.add_subcommand(
    "evaluate", "Run an evaluation protocol (DESIGN section 6); results go to a JSON file");
  evaluate->require_subcommand(1);

  auto synthetic = std::make_shared<SyntheticCommandOptions>();
  CLI::App* p1 = evaluate->add_subcommand("synthetic",
    "P1, the paper's synthetic experiment: 6 cameras, 900 noisy points, contours, misaligned data; "
    "TRE of V-IMLOP, its baselines and Open3D peers");
  CLI::Option* mesh =
    p1->add_option("--mesh", synthetic->mesh, "airway surface (CT frame, normals into the air)");
  CLI::Option* ct =
    p1->add_option("--ct", synthetic->ct, "CT volume whose airway is segmented with the defaults");
  mesh->excludes(ct);
  p1->add_option("--out", synthetic->out, "result JSON file")->required();
  p1->add_option("--trials", synthetic->trials, "number of trials")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  p1->add_option("--seed", synthetic->seed, "random seed")->capture_default_str();
  p1->add_option(
      "--misalign-mm", synthetic->misalignMm, "range of the initial translation error, mm")
    ->capture_default_str();
  p1->add_option(
      "--misalign-deg", synthetic->misalignDeg, "range of the initial rotation error, degrees")
    ->capture_default_str();
  p1->add_option("--methods", synthetic->methods,
      std::string("comma-separated methods: ") + syntheticProtocolMethodNames())
    ->capture_default_str();
  p1->add_option("--threads", synthetic->threads, "threads per registration, 0 for all cores")
    ->capture_default_str();
  p1->add_option("--save-trial", synthetic->saveTrial,
    "also write trial 0 and its registration (by the first of vimlop, imlp, trimmed-icp in "
    "--methods) as a result folder for vimlop report, with the model rendered from the true "
    "cameras as frame pictures");
  p1->callback([synthetic] { runSynthetic(*synthetic); });

  auto video = std::make_shared<VideoCommandOptions>();
  CLI::App* p2 = evaluate->add_subcommand("video",
    "P2, the paper's simulated-video experiment: a virtual endoscope sequence, contour detection, "
    "SfM, tracker scale, a perturbed start; camera errors of V-IMLOP and IMLP");
  CLI::Option* videoMesh =
    p2->add_option("--mesh", video->mesh, "airway surface (CT frame, normals into the air)");
  CLI::Option* videoCt =
    p2->add_option("--ct", video->ct, "CT volume whose airway is segmented with the defaults");
  videoMesh->excludes(videoCt);
  p2->add_option("--out", video->out, "result JSON file")->required();
  p2->add_option("--frames", video->frames, "frames of the sequence")
    ->capture_default_str()
    ->check(CLI::Range(3, 1000));
  p2->add_option("--seed", video->seed, "random seed (path, texture, noise, start)")
    ->capture_default_str();
  p2->add_option("--sfm", video->sfm, "structure from motion: builtin or colmap")
    ->capture_default_str();
  p2->add_option("--colmap", video->colmap, "the COLMAP executable (with --sfm colmap)")
    ->capture_default_str();
  p2->add_option("--work", video->work, "folder for COLMAP's work (default: OUT.work)");
  p2->add_option("--perturb-mm", video->perturbMm, "range of the initial translation error, mm")
    ->capture_default_str();
  p2->add_option("--perturb-deg", video->perturbDeg, "range of the initial rotation error, degrees")
    ->capture_default_str();
  p2->add_option("--init", video->init,
      "start: perturbed (the truth moved by --perturb-mm/--perturb-deg) or canonical "
      "(multi-start from canonical poses)")
    ->capture_default_str();
  p2->add_option("--upright-deg", video->uprightDeg,
      "with --init canonical: the simulated scope's image up stays this close to superior, deg")
    ->capture_default_str()
    ->check(CLI::Range(0.0, 180.0));
  p2->add_option("--canonical-spacing-mm", video->canonicalSpacingMm,
      "with --init canonical: distance between canonical positions, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  p2->add_option("--scale-factors", video->scaleFactors,
      "with --init canonical: variations of the tracker's scale per start")
    ->capture_default_str();
  p2->add_option("--screen-iterations", video->screeningIterations,
      "with --init canonical: iterations of every start before the finalists are chosen "
      "(0: run all fully)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  p2->add_option("--finalists", video->finalists,
      "with --init canonical: starts run fully, at every scale factor")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  p2->add_option("--failure-threshold-px", video->failureThresholdPx,
      "contour error above which a result is flagged as a failure, px")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  p2->add_option("--threads", video->threads, "threads per registration, 0 for all cores")
    ->capture_default_str();
  p2->callback([video] { runVideo(*video); });

  auto perturbation = std::make_shared<PerturbationCommandOptions>();
  CLI::App* p3 = evaluate->add_subcommand("perturbation",
    "P3: robustness to the initial pose on a simulated sequence; OUT/p3.json, OUT/runs.json and "
    "the Fig. 3 report in OUT/report");
  CLI::Option* p3Mesh =
    p3->add_option("--mesh", perturbation->mesh, "airway surface (CT frame, normals into the air)");
  CLI::Option* p3Ct = p3->add_option(
    "--ct", perturbation->ct, "CT volume whose airway is segmented with the defaults");
  p3Mesh->excludes(p3Ct);
  p3->add_option("--out", perturbation->out, "output folder")->required();
  p3->add_option("--offsets-mm", perturbation->offsets,
      "offsets of the start, each both mm of translation and degrees of rotation")
    ->capture_default_str();
  p3->add_option("--trials-per-offset", perturbation->trialsPerOffset, "registrations per offset")
    ->capture_default_str()
    ->check(CLI::Range(1, 10000));
  p3->add_option("--seed", perturbation->seed, "random seed (sequence and starts)")
    ->capture_default_str();
  p3->add_option("--frames", perturbation->frames, "frames of the sequence")
    ->capture_default_str()
    ->check(CLI::Range(2, 1000));
  p3->add_option("--success-mm", perturbation->successMm,
      "a run succeeds when its mean camera position error is at most this, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  p3->add_option("--threads", perturbation->threads, "threads over runs, 0 for all cores")
    ->capture_default_str();
  p3->add_flag("--no-report", perturbation->noReport, "skip the rendered report");
  p3->callback([perturbation] { runPerturbation(*perturbation); });
  return evaluate;
}

} // namespace vimlop
