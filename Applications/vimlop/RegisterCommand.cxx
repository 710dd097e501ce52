#include "RegisterCommand.h"

#include "CommandLine.h"
#include "PipelineFlags.h"
#include "PoseServingFlags.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Pipeline/RegistrationOutputs.h>
#include <vimlop/Pipeline/VideoRegistrationPipeline.h>
#include <vimlop/Rendering/OffscreenRendering.h>
#include <vimlop/Results/RegistrationRecordIO.h>
#include <vimlop/Server/PoseServing.h>

#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <tuple>

namespace vimlop
{

namespace
{

namespace fs = std::filesystem;

std::atomic<bool> interrupted{ false };

void onInterrupt(int)
{
  interrupted = true;
}

/// Ctrl-C asks the registration to stop; the previous handlers come back after.
class InterruptGuard
{
public:
  InterruptGuard()
  {
    interrupted = false;
    this->Previous = std::signal(SIGINT, onInterrupt);
    this->PreviousTerm = std::signal(SIGTERM, onInterrupt);
  }
  ~InterruptGuard()
  {
    std::signal(SIGINT, this->Previous);
    std::signal(SIGTERM, this->PreviousTerm);
  }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

private:
  void (*Previous)(int) = nullptr;
  void (*PreviousTerm)(int) = nullptr;
};

/// The command's flags: inputs and outputs here, every registration setting in `pipeline`.
struct RegisterOptions
{
  std::string ct;
  std::string mesh;
  std::string frames;
  std::string video;
  std::string intrinsics;
  std::string sfm = "builtin";
  std::string tracker;
  double fps = 30.0;
  double timeOffsetS = 0.0;
  double scale = 0.0;
  std::string init = "canonical";
  std::string method = "vimlop";
  std::string truth;
  VideoRegistrationOptions pipeline;
  int maxFrames = 1000;
  std::string out;
  bool force = false;
  bool json = false;
  bool printOptions = false;
  RegistrationOutputOptions outputs;
  bool serve = false;
  PoseServingOptions serving;
};

/// --init: manual:POSE.json, canonical or canonical:POSES.json, as a mode and a pose file.
std::pair<StartMode, std::string> parseInit(const std::string& text)
{
  if (text.rfind("manual:", 0) == 0 && text.size() > 7)
  {
    return { StartMode::Manual, text.substr(7) };
  }
  if (text == "canonical" || (text.rfind("canonical:", 0) == 0 && text.size() > 10))
  {
    return { StartMode::Canonical, text.size() > 10 ? text.substr(10) : std::string() };
  }
  throw Error(
    "--init: expected manual:POSE.json, canonical or canonical:POSES.json, got '" + text + "'");
}

/// --sfm: "builtin" -> "", "colmap:DIR" -> DIR.
std::string parseSfm(const std::string& text)
{
  if (text == "builtin")
  {
    return std::string();
  }
  if (text.rfind("colmap:", 0) == 0 && text.size() > 7)
  {
    return text.substr(7);
  }
  throw Error("--sfm: expected builtin or colmap:DIR, got '" + text + "'");
}

void runRegister(RegisterOptions o)
{
  const auto start = std::chrono::steady_clock::now();
  InterruptGuard guard;
  // In --json mode only the JSON reaches stdout, and only warnings and errors stderr.
  std::ostringstream quiet;
  std::ostream& log = o.json ? quiet : std::cerr;

  // Everything that can be checked before the work is checked first.
  o.pipeline.registration.method = registrationMethodFromString(o.method);
  if (o.printOptions)
  {
    std::cout << registrationOptionsJson(o.pipeline).dump(2) << std::endl;
    return;
  }
  if (fs::exists(o.out) && !o.force)
  {
    throw Error("'" + o.out + "': exists; choose another --out or add --force to replace it");
  }
  VideoRegistrationInputs inputs;
  inputs.meshPath = o.mesh;
  inputs.ctPath = o.ct;
  inputs.framesPath = o.frames.empty() ? o.video : o.frames;
  inputs.maxFrames = o.maxFrames;
  inputs.intrinsicsPath = o.intrinsics;
  inputs.colmapFolder = parseSfm(o.sfm);
  inputs.trackerPath = o.tracker;
  inputs.initialScale = o.scale;
  inputs.framesPerSecond = o.fps;
  inputs.timeOffsetS = o.timeOffsetS;
  std::tie(inputs.startMode, inputs.startPosesPath) = parseInit(o.init);
  if (o.tracker.empty() && !(o.scale > 0.0))
  {
    throw Error("give --tracker CSV or --scale S: SfM alone has no metric scale");
  }
  VideoRegistrationPipeline pipeline(o.pipeline);
  pipeline.setLog(&log);
  pipeline.setProgress([](const std::string&, double) { return !interrupted; });
  pipeline.prepare(inputs);
  const std::vector<FramePose> truthPoses =
    o.truth.empty() ? std::vector<FramePose>() : readFramePoses(o.truth);
  requireOffscreenRendering("vimlop register");
  try
  {
    pipeline.process();
  }
  catch (const PipelineCancelled&)
  {
    std::cerr << "vimlop: interrupted; no result was written\n";
    throw ExitRequest{ 130 };
  }
  const RegistrationResult& result = pipeline.result();
  if (interrupted)
  {
    std::cerr << "vimlop: interrupted; no result was written\n";
    throw ExitRequest{ 130 };
  }

  RegistrationRecord record = makeRegistrationRecord(
    pipeline, "vimlop register " + (o.frames.empty() ? o.video : o.frames), truthPoses, o.truth);
  if (!o.outputs.video && !o.outputs.report)
  {
    log << "vimlop register: result folder\n";
  }
  writeRegistrationOutputs(pipeline, record, o.out, o.fps, o.outputs, &log);

  // What the user reads.
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json summary =
    registrationSummaryJson(pipeline, record, (fs::path(o.out) / "result.json").string(), seconds);
  const MultiStartResult& outcome = pipeline.outcome();
  if (o.json)
  {
    std::cout << summary.dump(2) << std::endl;
  }
  else
  {
    std::printf("registered %zu frames (%zu SfM points) from %s (%zu candidates) in %.1f s: "
                "scale %.4f mm/unit, residual %.3f mm, contour error %.2f px%s\n",
      record.data.frames.size(), record.data.points.size(), record.confidence->init.c_str(),
      outcome.candidates.size(), seconds, result.sfmToCT.scale, result.residualErrorMm,
      result.contourErrorPx,
      outcome.failure ? " -- FLAGGED AS A FAILURE (above the threshold)" : "");
    if (record.truth)
    {
      std::printf("camera error against the truth: %.3f mm (max %.3f), %.3f deg (max %.3f)\n",
        summary["camera_position_error_mm"]["mean"].get<double>(),
        summary["camera_position_error_mm"]["max"].get<double>(),
        summary["camera_angle_error_deg"]["mean"].get<double>(),
        summary["camera_angle_error_deg"]["max"].get<double>());
    }
    std::printf("wrote '%s' (result.json, VTK files, registered video, report)\n", o.out.c_str());
  }
  if (outcome.failure)
  {
    if (o.serve)
    {
      std::cerr << "vimlop: warning: not serving poses of a result flagged as a failure\n";
    }
    throw ExitRequest{ 3 };
  }
  if (o.serve)
  {
    PoseServingOptions serving = o.serving;
    serving.label = "vimlop register";
    servePoses(serving, servedPosesOf(result));
  }
}

} // namespace

void addRegisterCommand(CLI::App& app)
{
  auto o = std::make_shared<RegisterOptions>();
  VideoRegistrationOptions& p = o->pipeline;
  CLI::App* c = app.add_subcommand("register",
    "Register an endoscopic video to a CT (V-IMLOP): result folder with result.json, VTK files, "
    "registered video and report. Exit code 3 when the result is flagged as a failure.");
  CLI::Option* ct = c->add_option("--ct", o->ct, "CT volume (its airway is segmented)");
  CLI::Option* mesh =
    c->add_option("--mesh", o->mesh, "airway surface (CT frame, normals into the air)");
  ct->excludes(mesh);
  CLI::Option* frames = c->add_option("--frames", o->frames, "folder of frames");
  CLI::Option* video = c->add_option("--video", o->video, "video file");
  frames->excludes(video);
  c->add_option("--intrinsics", o->intrinsics, "camera intrinsics (OpenCV YAML/JSON/XML)")
    ->required();
  c->add_option("--sfm", o->sfm, "structure from motion: builtin or colmap:DIR (a sparse model)")
    ->capture_default_str();
  c->add_option(
    "--tracker", o->tracker, "tracker CSV (time_s,x_mm,y_mm,z_mm): initial scale (V14)");
  c->add_option("--fps", o->fps, "frame rate, for the frame times on the tracker's clock")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c->add_option(
     "--time-offset", o->timeOffsetS, "time of the first frame on the tracker's clock, s")
    ->capture_default_str();
  c->add_option("--scale", o->scale, "initial scale, mm per SfM unit (instead of the tracker's)")
    ->check(CLI::PositiveNumber);
  c->add_option("--init", o->init,
     "start: manual:POSE.json (the camera-to-CT pose of one frame, FramePose JSON), canonical "
     "(poses generated along the airway) or canonical:POSES.json (e.g. template poses warped "
     "by `vimlop warp`)")
    ->capture_default_str();
  c->add_option("--method", o->method, "vimlop, imlp or trimmed-icp")->capture_default_str();
  c->add_option("--truth", o->truth,
    "true camera poses (FramePose JSON, e.g. a simulation's poses.json): errors are reported");
  addPipelineOptions(*c, p);
  c->add_option("--max-frames", o->maxFrames, "read at most this many frames")
    ->capture_default_str()
    ->check(CLI::Range(2, 100000));
  c->add_option("--out", o->out, "result folder")->required();
  c->add_flag("--force", o->force, "replace the result folder's files if it exists");
  c->add_flag("--json", o->json, "print only a JSON summary on stdout");
  c->add_flag("--print-options", o->printOptions,
    "print the registration settings (defaults and flags) as JSON and exit");
  c->add_flag(
    "--no-video", [o](std::int64_t) { o->outputs.video = false; }, "skip the registered video");
  c->add_flag(
    "--no-report", [o](std::int64_t) { o->outputs.report = false; }, "skip the report");
  c->add_flag("--serve", o->serve,
    "then serve the poses over OpenIGTLink (CTFromSfM and VideoCamera_<frame>, RAS) until Ctrl-C; "
    "never a result flagged as a failure");
  addPoseServingOptions(*c, o->serving);
  c->callback(
    [o]
    {
      if (!o->printOptions && o->frames.empty() && o->video.empty())
      {
        throw Error("give --frames DIR or --video FILE");
      }
      runRegister(*o);
    });
}

} // namespace vimlop
