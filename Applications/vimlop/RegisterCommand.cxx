#include "RegisterCommand.h"

#include "CanonicalPoses.h"
#include "CommandLine.h"
#include "EmbreeRegistrationModel.h"
#include "Error.h"
#include "FramePoseIO.h"
#include "IntrinsicsIO.h"
#include "ModelLoading.h"
#include "MultiStartRegistration.h"
#include "OccludingContourDetector.h"
#include "OffscreenRendering.h"
#include "PoseServingFlags.h"
#include "RegisteredVideo.h"
#include "RegistrationMetrics.h"
#include "RegistrationRecordIO.h"
#include "RegistrationReport.h"
#include "Statistics.h"
#include "VideoEvaluation.h"
#include "VideoInput.h"

#include <CLI/CLI.hpp>

#include <vtkVersion.h>

#include <opencv2/core/version.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

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

/// Ctrl-C asks the registration to stop; the previous handler comes back after.
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
  VideoEvaluationOptions registration; ///< noise, scale bound, V11, threads
  double trimFraction = RegistrationOptions().trimFraction;
  double chiSquareProbability = RegistrationOptions().chiSquareProbability;
  std::string scaleFactors = "0.9,1,1.1";
  double canonicalSpacingMm = CanonicalPoseOptions().spacingMm;
  int maxFrames = 1000;
  std::string out;
  bool force = false;
  bool json = false;
  bool noVideo = false;
  bool noReport = false;
  bool serve = false;
  PoseServingOptions serving;
};

/// Where the user asked the start to come from.
struct InitChoice
{
  enum class Kind
  {
    Manual,
    Canonical
  } kind = Kind::Canonical;
  std::string file;
};

InitChoice parseInit(const std::string& text)
{
  InitChoice c;
  if (text.rfind("manual:", 0) == 0 && text.size() > 7)
  {
    c.kind = InitChoice::Kind::Manual;
    c.file = text.substr(7);
  }
  else if (text == "canonical" || (text.rfind("canonical:", 0) == 0 && text.size() > 10))
  {
    c.kind = InitChoice::Kind::Canonical;
    c.file = text.size() > 10 ? text.substr(10) : std::string();
  }
  else
  {
    throw Error(
      "--init: expected manual:POSE.json, canonical or canonical:POSES.json, got '" + text + "'");
  }
  return c;
}

/// "builtin" -> "", "colmap:DIR" -> DIR.
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

void checkInterrupted()
{
  if (interrupted)
  {
    std::cerr << "vimlop: interrupted; no result was written\n";
    throw ExitRequest{ 130 };
  }
}

void runRegister(const RegisterOptions& o)
{
  const auto start = std::chrono::steady_clock::now();
  InterruptGuard guard;
  // In --json mode only the JSON reaches stdout, and only warnings and errors stderr.
  std::ostringstream quiet;
  std::ostream& log = o.json ? quiet : std::cerr;
  auto warn = [&](const std::string& text) { std::cerr << "vimlop: warning: " << text << "\n"; };

  // Everything that can be checked before the work is checked first.
  if (fs::exists(o.out) && !o.force)
  {
    throw Error("'" + o.out + "': exists; choose another --out or add --force to replace it");
  }
  const InitChoice init = parseInit(o.init);
  const std::string colmapFolder = parseSfm(o.sfm);
  const RegistrationMethod method = registrationMethodFromString(o.method);
  if (o.tracker.empty() && !(o.scale > 0.0))
  {
    throw Error("give --tracker CSV or --scale S: SfM alone has no metric scale");
  }
  const std::vector<double> scaleFactors = parseNumbers(o.scaleFactors, "--scale-factors");
  std::optional<TrackerTrajectory> tracker;
  if (!o.tracker.empty())
  {
    std::vector<std::string> warnings;
    tracker = TrackerTrajectory::readCsv(o.tracker, &warnings);
    for (const std::string& w : warnings)
    {
      warn(w);
    }
  }
  std::vector<FramePose> manualPoses;
  if (init.kind == InitChoice::Kind::Manual)
  {
    manualPoses = readFramePoses(init.file);
    if (manualPoses.empty())
    {
      throw Error("'" + init.file + "': holds no pose");
    }
  }
  std::vector<FramePose> truthPoses;
  if (!o.truth.empty())
  {
    truthPoses = readFramePoses(o.truth);
  }
  requireOffscreenRendering("vimlop register");
  const std::string framesPath = o.frames.empty() ? o.video : o.frames;
  const FrameSequence sequence = FrameSequence::load(framesPath, o.maxFrames);
  const PinholeCamera k = readIntrinsics(o.intrinsics);
  const std::vector<cv::Mat> frames = idealFrames(sequence, k, framesPath, o.intrinsics, &log);
  if (tracker)
  {
    checkTrackerOverlap(*tracker, frameTimesS(frames.size(), o.fps, o.timeOffsetS));
  }

  log << "vimlop register: model\n";
  const TriangleMesh mesh = airwayMeshFrom(o.mesh, o.ct);
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  // Canonical poses before the video work, so that a bad pose file fails fast.
  std::vector<CameraPose> canonicalPoses;
  if (init.kind == InitChoice::Kind::Canonical)
  {
    if (init.file.empty())
    {
      CanonicalPoseOptions generation;
      generation.spacingMm = o.canonicalSpacingMm;
      canonicalPoses = makeCanonicalPoses(model, generation);
    }
    else
    {
      int dropped = 0;
      for (const FramePose& p : readFramePoses(init.file))
      {
        if (model.isInside(p.cameraToWorld.centre))
        {
          canonicalPoses.push_back(p.cameraToWorld);
        }
        else
        {
          ++dropped;
        }
      }
      if (dropped > 0)
      {
        warn(std::to_string(dropped) + " canonical poses of '" + init.file +
          "' lie outside the patient's airway; dropped");
      }
      if (canonicalPoses.empty())
      {
        throw Error("'" + init.file + "': no canonical pose lies inside the patient's airway");
      }
    }
  }
  checkInterrupted();

  log << "vimlop register: contours of " << frames.size() << " frames\n";
  const OccludingContourDetector detector{ OccludingContourDetector::Options() };
  std::vector<std::vector<ContourPoint>> contours;
  for (const cv::Mat& frame : frames)
  {
    contours.push_back(detector.detect(frame));
  }
  checkInterrupted();

  std::vector<std::string> names;
  for (int f = 0; f < sequence.size(); ++f)
  {
    names.push_back(sequence.name(f));
  }
  PinholeCamera ideal = k;
  ideal.distortion.resize(0);
  const SfmReconstruction sfm = reconstructFrames(frames, names, ideal, colmapFolder, &log);
  if (sfm.numberOfRegisteredFrames() < 2 || sfm.points.size() < 10)
  {
    throw Error("SfM registered " + std::to_string(sfm.numberOfRegisteredFrames()) +
      " frames and " + std::to_string(sfm.points.size()) + " points; too few to register");
  }
  checkInterrupted();

  // V14: the initial scale.
  double s0 = o.scale;
  if (tracker)
  {
    const TrackerScaleResult fromTracker =
      scaleFromTracker(*tracker, sfm, frameTimesS(sfm.frames.size(), o.fps, o.timeOffsetS), &log);
    if (o.scale > 0.0)
    {
      const double ratio = fromTracker.scale / o.scale;
      if (ratio > o.registration.scaleBoundFactor || ratio < 1.0 / o.registration.scaleBoundFactor)
      {
        warn("the tracker's scale " + std::to_string(fromTracker.scale) +
          " disagrees with --scale " + std::to_string(o.scale) + " by more than the scale bound; " +
          "using --scale");
      }
    }
    else
    {
      s0 = fromTracker.scale;
    }
  }
  log << "vimlop register: initial scale " << s0 << " mm per SfM unit\n";

  // The registration data: registered frames with their contours, points with covariances.
  RegistrationData data;
  std::vector<int> frameOf;
  for (size_t f = 0; f < sfm.frames.size(); ++f)
  {
    if (!sfm.frames[f].registered)
    {
      continue;
    }
    VideoFrame frame;
    frame.frameId = static_cast<int>(f);
    frame.intrinsics = ideal;
    frame.cameraToSfm = sfm.frames[f].cameraToSfm;
    frame.contour = contours[f];
    data.frames.push_back(frame);
    frameOf.push_back(static_cast<int>(f));
  }
  const double floorMm = o.registration.pointNoiseFloorMm;
  for (const SfmReconstruction::Point& p : sfm.points)
  {
    data.points.push_back(p.position);
    data.pointCovariances.push_back(
      s0 * s0 * p.covariance + floorMm * floorMm * Eigen::Matrix3d::Identity());
  }
  RegistrationOptions options = videoRegistrationOptions(s0, o.registration, method);
  options.trimFraction = o.trimFraction;
  options.chiSquareProbability = o.chiSquareProbability;

  // The starts.
  std::vector<SimilarityTransform> starts;
  std::string initName;
  if (init.kind == InitChoice::Kind::Manual)
  {
    const FramePose& pose = manualPoses.front();
    auto it = std::find_if(data.frames.begin(), data.frames.end(),
      [&](const VideoFrame& f) { return f.frameId == pose.frameId; });
    if (it == data.frames.end())
    {
      throw Error("'" + init.file + "': frame " + std::to_string(pose.frameId) +
        " is not a frame SfM registered; give the pose of another frame");
    }
    starts.push_back(startFromCameraPose(pose.cameraToWorld, it->cameraToSfm, s0));
    initName = "manual";
  }
  else
  {
    int anchor = 0;
    starts = canonicalStarts(data, s0, canonicalPoses, &anchor);
    log << "vimlop register: " << canonicalPoses.size() << " canonical poses, frame " << anchor
        << " placed at each\n";
    initName = "canonical";
  }
  checkInterrupted();

  // Register: a multi-start (one start is a multi-start of one).
  MultiStartOptions multi = o.registration.multiStart;
  multi.registration = options;
  multi.scaleFactors = starts.size() > 1 ? scaleFactors : std::vector<double>{ 1.0 };
  multi.threads = o.registration.threads;
  MultiStartResult outcome;
  if (starts.size() == 1)
  {
    // A single start uses every thread inside the registration instead.
    outcome.candidates.resize(1);
    outcome.candidates[0].initialSfmToCT = starts[0];
    outcome.best = registerVideo(model, data, starts[0], options,
      [&](const IterationRecord& r)
      {
        if (r.iteration % 10 == 0)
        {
          log << "vimlop register: iteration " << r.iteration << ", contour error "
              << r.contourErrorPx << " px\n";
        }
        return !interrupted;
      });
    outcome.bestCandidate = 0;
    outcome.failureThresholdPx = multi.failureContourErrorPx;
    outcome.failure = isFlaggedAsFailure(outcome.best, multi);
  }
  else
  {
    try
    {
      outcome = registerMultiStart(model, data, starts, multi,
        [&](const char* phase, int done, int total)
        {
          if (done == total || done % 10 == 0)
          {
            log << "vimlop register: " << phase << " " << done << "/" << total << "\n";
          }
          return !interrupted;
        });
    }
    catch (const Error&)
    {
      checkInterrupted();
      throw;
    }
  }
  checkInterrupted();
  const RegistrationResult& result = outcome.best;

  const double scaleChange = result.sfmToCT.scale / s0;
  if (scaleChange > 0.98 * o.registration.scaleBoundFactor ||
    scaleChange < 1.02 / o.registration.scaleBoundFactor)
  {
    warn("the registration ended at its scale bound (scale " +
      std::to_string(result.sfmToCT.scale) + ", initial " + std::to_string(s0) +
      "): the tracker's scale may be wrong");
  }

  // The result folder: result.json last, so that a folder holding one is complete.
  std::error_code ec;
  fs::remove(fs::path(o.out) / "result.json", ec);
  fs::create_directories(fs::path(o.out) / "frames", ec);
  if (ec)
  {
    throw Error("'" + o.out + "': cannot create the folder (" + ec.message() + ")");
  }
  RegistrationRecord record;
  record.source = "vimlop register " + framesPath;
  record.model = mesh;
  record.data = data;
  record.options = options;
  record.initialSfmToCT = outcome.candidates[outcome.bestCandidate].initialSfmToCT;
  record.result = result;
  for (size_t j = 0; j < data.frames.size(); ++j)
  {
    char name[64];
    std::snprintf(name, sizeof name, "frames/frame-%04d.png", data.frames[j].frameId);
    if (!cv::imwrite((fs::path(o.out) / name).string(), frames[frameOf[j]]))
    {
      throw Error("'" + (fs::path(o.out) / name).string() + "': cannot write the frame");
    }
    record.frameImages.push_back(name);
  }
  record.confidence = RegistrationRecord::Confidence{ outcome.failure, outcome.failureThresholdPx,
    initName, static_cast<int>(outcome.candidates.size()), outcome.bestCandidate };
  record.versions = { { "vtk", vtkVersion::GetVTKVersion() }, { "opencv", CV_VERSION } };
  if (!truthPoses.empty())
  {
    std::vector<CameraPose> truthPerSfmFrame(sfm.frames.size());
    std::vector<bool> known(sfm.frames.size(), false);
    for (const FramePose& p : truthPoses)
    {
      if (p.frameId >= 0 && p.frameId < static_cast<int>(sfm.frames.size()))
      {
        truthPerSfmFrame[p.frameId] = p.cameraToWorld;
        known[p.frameId] = true;
      }
    }
    RegistrationRecord::GroundTruth truth;
    bool complete = true;
    for (int f : frameOf)
    {
      complete = complete && known[f];
      truth.camerasCT.push_back(truthPerSfmFrame[f]);
    }
    if (!complete)
    {
      throw Error("'" + o.truth + "': has no pose for some registered frames");
    }
    truth.sfmToCT = similarityFromCameras(sfm, truthPerSfmFrame);
    record.truth = truth;
  }
  checkInterrupted();
  if (!o.noVideo)
  {
    log << "vimlop register: registered video\n";
    writeRegisteredVideo(record, o.out, o.fps);
  }
  writeCameraPath(result, (fs::path(o.out) / "camera-path.vtp").string());
  writeRegistrationRecord(record, o.out);
  if (!o.noReport)
  {
    log << "vimlop register: report\n";
    RegistrationReport::write(
      &record, o.out, {}, (fs::path(o.out) / "report").string(), RegistrationReport::Options());
  }

  // What the user reads.
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json summary = { { "result", (fs::path(o.out) / "result.json").string() },
    { "frames", data.frames.size() }, { "points", data.points.size() },
    { "scale", result.sfmToCT.scale }, { "init", initName },
    { "candidates", outcome.candidates.size() }, { "termination", toString(result.termination) },
    { "residual_error_mm", result.residualErrorMm }, { "contour_error_px", result.contourErrorPx },
    { "failure", outcome.failure }, { "failure_threshold_px", outcome.failureThresholdPx },
    { "runtime_s", seconds } };
  if (record.truth)
  {
    std::vector<double> position;
    std::vector<double> angle;
    for (size_t j = 0; j < result.frames.size(); ++j)
    {
      position.push_back(
        cameraPositionError(result.frames[j].cameraToCT, record.truth->camerasCT[j]));
      angle.push_back(cameraAngleErrorDeg(result.frames[j].cameraToCT, record.truth->camerasCT[j]));
    }
    const Summary p = summarize(position);
    const Summary a = summarize(angle);
    summary["camera_position_error_mm"] = { { "mean", p.mean }, { "max", p.max } };
    summary["camera_angle_error_deg"] = { { "mean", a.mean }, { "max", a.max } };
  }
  if (o.json)
  {
    std::cout << summary.dump(2) << std::endl;
  }
  else
  {
    std::printf("registered %zu frames (%zu SfM points) from %s (%zu candidates) in %.1f s: "
                "scale %.4f mm/unit, residual %.3f mm, contour error %.2f px%s\n",
      data.frames.size(), data.points.size(), initName.c_str(), outcome.candidates.size(), seconds,
      result.sfmToCT.scale, result.residualErrorMm, result.contourErrorPx,
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
      warn("not serving poses of a result flagged as a failure");
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
  c->add_option("--point-noise-mm", o->registration.pointNoiseFloorMm,
     "std added to every SfM point's covariance, mm")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c->add_option("--contour-variance-px2", o->registration.contourVariancePx2,
     "contour position noise Σ2d, px² (paper: 1 for video)")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c->add_option(
     "--kappa", o->registration.kappa, "contour orientation concentration κ (paper: 200)")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c->add_option("--trim", o->trimFraction, "initial trim ratio p_t of 3-D pairs")
    ->capture_default_str()
    ->check(CLI::Range(0.0, 0.9));
  c->add_option("--chi2-p", o->chiSquareProbability, "chi-square outlier test probability")
    ->capture_default_str()
    ->check(CLI::Range(0.5, 0.99999));
  c->add_option("--scale-bound", o->registration.scaleBoundFactor,
     "scale bounds: the initial scale divided and multiplied by this")
    ->capture_default_str()
    ->check(CLI::Range(1.0001, 10.0));
  c->add_option("--max-iterations", o->registration.maxIterations, "iteration cap per start")
    ->capture_default_str()
    ->check(CLI::Range(1, 100000));
  c->add_option("--threads", o->registration.threads, "threads, 0 for all cores")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c->add_option(
     "--scale-factors", o->scaleFactors, "canonical: variations of the initial scale per start")
    ->capture_default_str();
  c->add_option("--screen-iterations", o->registration.multiStart.screeningIterations,
     "canonical: iterations of every start before the finalists are chosen (0: all run fully)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c->add_option("--finalists", o->registration.multiStart.finalists,
     "canonical: starts run fully, at every scale factor")
    ->capture_default_str()
    ->check(CLI::Range(1, 100000));
  c->add_option("--canonical-spacing-mm", o->canonicalSpacingMm,
     "canonical: distance between generated canonical positions, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c->add_option("--failure-threshold-px", o->registration.multiStart.failureContourErrorPx,
     "contour error above which the result is flagged as a failure, px (calibrated on P3)")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c->add_option("--max-frames", o->maxFrames, "read at most this many frames")
    ->capture_default_str()
    ->check(CLI::Range(2, 100000));
  c->add_option("--out", o->out, "result folder")->required();
  c->add_flag("--force", o->force, "replace the result folder's files if it exists");
  c->add_flag("--json", o->json, "print only a JSON summary on stdout");
  c->add_flag("--no-video", o->noVideo, "skip the registered video");
  c->add_flag("--no-report", o->noReport, "skip the report");
  c->add_flag("--serve", o->serve,
    "then serve the poses over OpenIGTLink (CTFromSfM and VideoCamera_<frame>, RAS) until Ctrl-C; "
    "never a result flagged as a failure");
  addPoseServingOptions(*c, o->serving);
  c->callback(
    [o]
    {
      if (o->frames.empty() && o->video.empty())
      {
        throw Error("give --frames DIR or --video FILE");
      }
      runRegister(*o);
    });
}

} // namespace vimlop
