#include "CommandLine.h"
#include "Commands.h"
#include <vimlop/Cohort/CommandLineWords.h>
#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/ProcessMemory.h>
#include <vimlop/Core/TeeStream.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Pipeline/RegistrationOutputs.h>
#include <vimlop/Pipeline/VideoRegistrationPipeline.h>
#include <vimlop/Rendering/OffscreenRendering.h>
#include <vimlop/Results/ResultFolderTransaction.h>
#include <vimlop/Server/PoseServing.h>

#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>

namespace vimlop
{

namespace
{

/// --serve from the moment the result is usable, beside the slow outputs: the
/// poses are served in a thread of their own until Ctrl-C or --duration-s;
/// leaving early (an output failed) stops it.
class EarlyServing
{
public:
  EarlyServing() = default;
  EarlyServing(const EarlyServing&) = delete;
  EarlyServing& operator=(const EarlyServing&) = delete;
  ~EarlyServing()
  {
    this->Stop = true;
    if (this->Thread.joinable())
    {
      this->Thread.join();
    }
  }

  /// @brief Starts serving `poses` (once).
  void start(PoseServingOptions options, ServedPoses poses)
  {
    options.keepServing = [this] { return !this->Stop; };
    this->Thread = std::thread(
      [this, options = std::move(options), poses = std::move(poses)]
      {
        try
        {
          servePoses(options, poses);
        }
        catch (...)
        {
          this->Failure = std::current_exception();
        }
      });
  }

  /// @brief Waits until serving ends (Ctrl-C or the duration); rethrows its error.
  void wait()
  {
    if (this->Thread.joinable())
    {
      this->Thread.join();
    }
    if (this->Failure)
    {
      std::rethrow_exception(this->Failure);
    }
  }

private:
  std::atomic<bool> Stop{ false };
  std::exception_ptr Failure;
  std::thread Thread;
};

/// The command's flags: the pipeline's inputs and settings, and what to do with the result.
struct RegisterCommand
{
  VideoRegistrationInputs inputs;
  VideoRegistrationOptions pipeline;
  std::string video, sfm = "builtin", init = "canonical", method = "vimlop", truth, out;
  bool force = false, json = false, printOptions = false, serve = false, timings = false;
  /// The options given, as a config file (TOML) to run it again.
  std::string configText;
  RegistrationOutputOptions outputs;
  PoseServingOptions serving;
};

void runRegister(RegisterCommand c)
{
  const auto start = std::chrono::steady_clock::now();
  const InterruptGuard guard;
  // In --json mode only the JSON reaches stdout, and only warnings and errors stderr.
  std::ostringstream quiet;
  std::ostream& terminal = c.json ? quiet : std::cerr;

  // Everything that can be checked before the work is checked first.
  c.pipeline.registration.method = registrationMethodFromString(c.method);
  if (c.printOptions)
  {
    std::cout << registrationOptionsJson(c.pipeline).dump(2) << std::endl;
    return;
  }
  VideoRegistrationInputs& inputs = c.inputs;
  if (inputs.framesPath.empty())
  {
    inputs.framesPath = c.video;
  }
  inputs.setStructureFromMotion(c.sfm, "--sfm");
  inputs.setStart(c.init, "--init");
  if (inputs.trackerPath.empty() && inputs.trackerTransform.empty() && !(inputs.initialScale > 0.0))
  {
    throw Error("give --tracker CSV, --tracker-transform NAME (of a tracked sequence) or --scale "
                "S: SfM alone has no metric scale");
  }
  // The result folder is checked and locked before the work (and after the
  // flags, so a mistyped flag is reported as such): everything is
  // written beside it and renamed into place at the end, so a failure, Ctrl-C
  // or kill leaves the old folder or none (Documentation/UserGuide.md).
  std::string note;
  ResultFolderTransaction folder(c.out,
    c.force ? ResultFolderTransaction::Existing::Replace
            : ResultFolderTransaction::Existing::Refuse,
    &note);
  // The run's log in its result folder: the command, the progress lines and
  // warnings as the terminal shows them, the summary.
  const std::string logPath = (std::filesystem::path(folder.stagingFolder()) / "log.txt").string();
  std::ofstream logFile(logPath);
  if (!logFile)
  {
    throwFileError(logPath, "cannot write the log file");
  }
  logFile << joinCommandLine(commandWords()) << "\n";
  writeFileAtomically((std::filesystem::path(folder.stagingFolder()) / "config.toml").string(),
    "# vimlop register: the options of this run (vimlop register --config config.toml runs it "
    "again;\n# relative paths are relative to where it ran)\n" +
      c.configText);
  TeeStream log(terminal, logFile);
  if (!note.empty())
  {
    std::cerr << "vimlop: note: " << note << "\n";
    logFile << "vimlop: note: " << note << "\n";
  }
  VideoRegistrationPipeline pipeline(c.pipeline);
  pipeline.setLog(&log);
  pipeline.setWarningHandler(
    [&](const std::string& warning)
    {
      std::cerr << "vimlop: warning: " << warning << "\n";
      logFile << "vimlop: warning: " << warning << "\n";
    });
  pipeline.setProgress([](const std::string&, double) { return !InterruptGuard::requested(); });
  pipeline.prepare(inputs);
  const std::vector<FramePose> truth =
    c.truth.empty() ? std::vector<FramePose>() : readFramePoses(c.truth);
  requireOffscreenRendering("vimlop register");
  try
  {
    pipeline.process();
  }
  catch (const PipelineCancelled&)
  {
  }
  if (InterruptGuard::requested())
  {
    std::cerr << "vimlop: interrupted; no result was written\n";
    throw ExitRequest{ 130 };
  }

  // The pipeline's stages, then the record's and the outputs' (the order they run).
  StageTimings timings = pipeline.timings();
  const StageTimings::Stopwatch recordWatch;
  RegistrationRecord record =
    makeRegistrationRecord(pipeline, "vimlop register " + inputs.framesPath, truth, c.truth);
  record.commandLine = joinCommandLine(commandWords());
  timings.set("record", recordWatch);
  if (!c.outputs.video && !c.outputs.report)
  {
    log << "vimlop register: result folder\n";
  }
  EarlyServing serving;
  // The poses are written first: from then on the result is usable (and --json's
  // "result_usable_s" says when); the pictures, video, report and result.json follow.
  c.outputs.onResultUsable = [&](const std::string& posesPath)
  {
    const double usableS =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    timings.mark("result_usable", usableS);
    log << formatText("vimlop register: result usable after %.1f s: '%s' (the folder becomes "
                      "'%s' when complete)\n",
      usableS, posesPath.c_str(), c.out.c_str());
    log.flush();
    if (c.serve && (!pipeline.outcome().failure || c.serving.allowFlagged))
    {
      c.serving.label = "vimlop register";
      serving.start(c.serving, servedPosesOf(record));
    }
  };
  c.outputs.keepGoing = [] { return !InterruptGuard::requested(); };
  try
  {
    writeRegistrationOutputs(pipeline, record, folder.stagingFolder(), pipeline.framesPerSecond(),
      c.outputs, &log, &timings);
  }
  catch (const PipelineCancelled&)
  {
    std::cerr << "vimlop: interrupted; no result was written\n";
    throw ExitRequest{ 130 };
  }
  catch (const Error&)
  {
    folder.keepStaging(); // the message names the registered poses in it
    throw;
  }
  folder.commit();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json summary = registrationSummaryJson(
    pipeline, record, (std::filesystem::path(c.out) / "result.json").string(), seconds, &timings);
  // This process's own peak (since its exec), for `vimlop evaluate speed`.
  if (const double peakMiB = peakResidentMiBOfThisProcess(); peakMiB >= 0.0)
  {
    summary["peak_resident_mib"] = peakMiB;
  }
  // The folder is committed (renamed): its log file stays open and takes the summary too.
  for (const std::string& line : registrationSummaryLines(summary))
  {
    logFile << line << "\n";
  }
  logFile.flush();
  if (c.json)
  {
    std::cout << summary.dump(2) << std::endl;
  }
  else
  {
    printLines(registrationSummaryLines(summary));
    if (c.timings)
    {
      std::cout << "timings: " << timings.summaryLine() << "\n";
    }
    std::cout << "wrote '" << c.out << "' (registered-poses.json, result.json, VTK files"
              << (c.outputs.video ? ", registered video" : "")
              << (c.outputs.report ? ", report" : "") << ")\n";
  }
  if (pipeline.outcome().failure)
  {
    if (c.serve && !c.serving.allowFlagged)
    {
      std::cerr << "vimlop: warning: not serving poses of a result flagged as a failure (pass "
                   "--allow-flagged to serve them with a STATUS message that says so)\n";
    }
    serving.wait();
    throw ExitRequest{ 3 };
  }
  serving.wait();
}

} // namespace

void addRegisterCommand(CLI::App& app)
{
  auto c = std::make_shared<RegisterCommand>();
  VideoRegistrationInputs& in = c->inputs;
  CLI::App* r = app.add_subcommand("register",
    "Register an endoscopic video to a CT (V-IMLOP): result folder with result.json, VTK files, "
    "registered video and report. Exit code 3 when the result is flagged as a failure.");
  r->add_option("--ct", in.ctPath, "CT volume (its airway is segmented)")
    ->excludes(
      r->add_option("--mesh", in.meshPath, "airway surface (CT frame, normals into the air)"));
  r->add_option("--frames", in.framesPath,
     "folder of frames, or a tracked sequence of PLUS or 3D Slicer (.igs.mha, .igs.nrrd, "
     ".seq.nrrd, .seq.mha) with its frames' timestamps")
    ->excludes(r->add_option("--video", c->video, "video file"));
  r->add_option("--intrinsics", in.intrinsicsPath, "camera intrinsics (OpenCV YAML/JSON/XML)")
    ->required();
  r->add_option("--sfm", c->sfm,
     "structure from motion: builtin, colmap (COLMAP run on the frames, --colmap-executable), "
     "colmap:DIR (a COLMAP sparse model) or FILE.json (the output of vimlop sfm, reused; frames "
     "matched by name)")
    ->capture_default_str();
  r->add_option("--colmap-executable", in.colmapExecutable, "the COLMAP program of --sfm colmap")
    ->capture_default_str();
  r->add_option("--contours", in.contoursFile,
    "occluding contours already detected: the output of vimlop contours (with --intrinsics when "
    "the lens has a distortion), reused instead of detecting them (frames matched by name)");
  r->add_option("--tracker", in.trackerPath,
    "tracker CSV (time_s,x_mm,y_mm,z_mm), or a tracked sequence with --tracker-transform: "
    "initial scale (V14)");
  r->add_option("--tracker-transform", in.trackerTransform,
    "the transform of a tracked sequence that carries the scope, e.g. ProbeToTracker: read from "
    "--tracker, or from --frames when it is a tracked sequence and --tracker is not given");
  r->add_option("--tracker-to-ct", in.trackerToCTPath,
    "the tracker registered to the patient, as 3D Slicer saves its TrackerToRAS transform (ITK "
    ".tfm/.h5): the tracked camera (a 6-DOF sensor in the camera's own frame: a tracked "
    "sequence's transform, or a tracker CSV with qw,qx,qy,qz) turns the canonical starts and is "
    "one more start, a rotation prior");
  r->add_option("--fps", in.framesPerSecond,
     "frame rate, for the frame times on the tracker's clock; overrides the frames' own "
     "timestamps (a tracked sequence) or rate (a video file), with a warning when they "
     "disagree (default: the frames' own, else 30)")
    ->check(CLI::PositiveNumber);
  r->add_option(
     "--time-offset", in.timeOffsetS, "time of the first frame on the tracker's clock, s")
    ->capture_default_str();
  r->add_option(
     "--scale", in.initialScale, "initial scale, mm per SfM unit (instead of the tracker's)")
    ->check(CLI::PositiveNumber);
  r->add_option("--init", c->init,
     "start: manual:POSE.json (the camera-to-CT pose of one frame, FramePose JSON), canonical "
     "(poses generated along the airway) or canonical:POSES.json (e.g. template poses warped "
     "by `vimlop warp`)")
    ->capture_default_str();
  r->add_option("--method", c->method, "vimlop, imlp or trimmed-icp")->capture_default_str();
  r->add_option("--truth", c->truth,
    "true camera poses (FramePose JSON, e.g. a simulation's poses.json): errors are reported");
  addPipelineOptions(*r, c->pipeline);
  r->add_option("--max-frames", in.maxFrames, "read at most this many frames")
    ->capture_default_str()
    ->check(CLI::Range(2, 100000));
  r->add_option("--out", c->out, "result folder")->required();
  r->add_flag("--force", c->force, "replace the result folder's files if it exists");
  r->add_flag("--json", c->json,
    "print only a JSON summary on stdout (with each stage's wall and CPU time as \"timings\")");
  r->add_flag("--timings", c->timings,
    "also print one line of each stage's wall time (frames, model, contours, sfm, ..., report)");
  r->add_flag("--print-options", c->printOptions,
    "print the registration settings (defaults and flags) as JSON and exit");
  r->add_flag(
    "--no-video", [c](std::int64_t) { c->outputs.video = false; }, "skip the registered video");
  r->add_flag(
    "--no-report", [c](std::int64_t) { c->outputs.report = false; }, "skip the report");
  r->add_flag("--serve", c->serve,
    "serve the poses over OpenIGTLink (CTFromSfM, the moving camera and a STATUS verdict, RAS) "
    "from the moment they are written (while the video and report are written) until Ctrl-C; "
    "a result flagged as a failure only with --allow-flagged");
  addPoseServingOptions(*r, c->serving);
  r->callback(
    [c, r]
    {
      if (!c->printOptions && c->inputs.framesPath.empty() && c->video.empty())
      {
        throw Error("give --frames DIR or --video FILE");
      }
      // What was given, from the command line and a config file alike.
      c->configText = "[register]\n" + r->config_to_str(false, true);
      runRegister(*c);
    });
}

} // namespace vimlop
