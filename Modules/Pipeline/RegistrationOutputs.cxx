#include <vimlop/Pipeline/RegistrationOutputs.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Pipeline/SimilarityFromCameras.h>
#include <vimlop/Pipeline/VideoRegistrationOptionTable.h>
#include <vimlop/Report/RegisteredVideo.h>
#include <vimlop/Report/RegistrationReport.h>
#include <vimlop/Results/InputIdentity.h>
#include <vimlop/Results/RecordJson.h>
#include <vimlop/Results/RegistrationRecordIO.h>

#include <vtkVersion.h>

#include <opencv2/core/version.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <ostream>

namespace vimlop
{

namespace fs = std::filesystem;

namespace
{

/// Runs one slow output; its error names it and says that the poses are there all the same.
template <typename Write>
void writeAfterThePoses(const char* what, const std::string& posesPath, Write write)
{
  try
  {
    write();
  }
  catch (const Error& e)
  {
    throw Error(std::string(what) + ": " + e.what() + " (the registered poses are in '" +
      posesPath + "'; the folder is incomplete: no result.json)");
  }
}

} // namespace

const char* registeredPosesFileName()
{
  return "registered-poses.json";
}

std::string writeRegisteredPoses(
  const VideoRegistrationPipeline& pipeline, const std::string& folder)
{
  const MultiStartResult& outcome = pipeline.outcome();
  const RegistrationResult& result = outcome.best;
  std::vector<FramePose> poses;
  for (const FrameResult& frame : result.frames)
  {
    poses.push_back({ frame.frameId, frame.cameraToCT });
  }
  nlohmann::json document = framePosesJson(poses);
  document["format"] = "vimlop-registered-poses";
  document["version"] = 1;
  document["sfm_to_ct"] = recordjson::transformJson(result.sfmToCT);
  document["failure"] = outcome.failure;
  document["failure_reason"] = outcome.failureReason;
  document["failure_threshold_px"] = outcome.failureThresholdPx;
  document["failure_residual_mm"] = outcome.failureResidualMm;
  document["contour_error_px"] = result.contourErrorPx;
  document["residual_error_mm"] = result.residualErrorMm;
  const std::string path = (fs::path(folder) / registeredPosesFileName()).string();
  writeFileAtomically(path, document.dump(2) + "\n");
  return path;
}

RegistrationRecord makeRegistrationRecord(const VideoRegistrationPipeline& pipeline,
  const std::string& source, const std::vector<FramePose>& truthPoses,
  const std::string& truthSource)
{
  const MultiStartResult& outcome = pipeline.outcome();
  RegistrationRecord record;
  record.source = source;
  record.model = pipeline.mesh();
  record.data = pipeline.data();
  record.options = pipeline.options().registrationOptions(pipeline.initialScale());
  record.initialSfmToCT = outcome.candidates[outcome.bestCandidate].initialSfmToCT;
  record.result = outcome.best;
  for (const VideoFrame& frame : record.data.frames)
  {
    record.frameImages.push_back(resultFrameImageName(frame.frameId));
  }
  record.frameTimesS = pipeline.frameTimesS();
  record.runWallS = pipeline.timings().totalWallS();
  record.confidence = RegistrationRecord::Confidence{ outcome.failure, outcome.failureThresholdPx,
    outcome.failureReason, pipeline.startMode() == StartMode::Manual ? "manual" : "canonical",
    static_cast<int>(outcome.candidates.size()), outcome.bestCandidate, outcome.failureResidualMm };
  record.versions = { { "vtk", vtkVersion::GetVTKVersion() }, { "opencv", CV_VERSION } };
  std::vector<bool> posed(pipeline.frameIds().size(), false);
  for (int f : pipeline.frameOf())
  {
    record.frameSources.push_back(pipeline.frameNames()[f]);
    posed[static_cast<size_t>(f)] = true;
  }
  const std::vector<double>& loadedTimesS = pipeline.loadedFrameTimesS();
  for (size_t f = 0; f < posed.size(); ++f)
  {
    if (!posed[f])
    {
      RegistrationRecord::FrameWithoutPose lost;
      lost.frameId = pipeline.frameIds()[f];
      lost.source = pipeline.frameNames()[f];
      if (f < loadedTimesS.size())
      {
        lost.timeS = loadedTimesS[f];
      }
      record.framesWithoutPose.push_back(lost);
    }
  }
  record.ctIdentity = pipeline.ctIdentity();
  record.inputs = pipeline.inputIdentities();
  if (!truthPoses.empty() && !record.inputs.empty())
  {
    std::vector<std::string> problems;
    for (RegistrationRecord::InputFile& truth :
      identifyInputs({ { "truth", truthSource } }, problems))
    {
      record.inputs.push_back(std::move(truth));
    }
    for (const std::string& problem : problems)
    {
      std::cerr << "vimlop: warning: " << problem << "\n";
    }
  }
  if (truthPoses.empty())
  {
    return record;
  }
  // The truth is keyed by frame id (a file's number), the SfM by index.
  const SfmReconstruction& sfm = pipeline.sfm();
  const std::vector<int>& ids = pipeline.frameIds();
  std::vector<CameraPose> truthPerSfmFrame(sfm.frames.size());
  std::vector<bool> known(sfm.frames.size(), false);
  for (const FramePose& p : truthPoses)
  {
    const auto at = std::find(ids.begin(), ids.end(), p.frameId);
    if (at != ids.end())
    {
      truthPerSfmFrame[static_cast<std::size_t>(at - ids.begin())] = p.cameraToWorld;
      known[static_cast<std::size_t>(at - ids.begin())] = true;
    }
  }
  RegistrationRecord::GroundTruth truth;
  for (int f : pipeline.frameOf())
  {
    if (!known[f])
    {
      throwFileError(truthSource,
        "has no pose for frame " + std::to_string(ids[f]) + " ('" + pipeline.frameNames()[f] +
          "'), which was registered");
    }
    truth.camerasCT.push_back(truthPerSfmFrame[f]);
  }
  truth.sfmToCT = similarityFromCameras(sfm, truthPerSfmFrame);
  record.truth = truth;
  return record;
}

void writeRegistrationOutputs(const VideoRegistrationPipeline& pipeline,
  const RegistrationRecord& record, const std::string& folder, double fps,
  const RegistrationOutputOptions& options, std::ostream* log, StageTimings* timings)
{
  StageTimings local;
  StageTimings& t = timings ? *timings : local;
  const auto goOn = [&]
  {
    if (options.keepGoing && !options.keepGoing())
    {
      throw PipelineCancelled();
    }
  };
  StageTimings::Stopwatch watch;
  std::error_code ec;
  fs::remove(fs::path(folder) / "result.json", ec);
  fs::create_directories(fs::path(folder) / "frames", ec);
  if (ec)
  {
    throwFileError(folder, "cannot create the folder (" + ec.message() + ")");
  }
  // The usable result first: everything after it only shows it.
  const std::string posesPath = writeRegisteredPoses(pipeline, folder);
  t.set("poses", watch);
  if (options.onResultUsable)
  {
    options.onResultUsable(posesPath);
  }

  watch = StageTimings::Stopwatch();
  const std::vector<int>& frameOf = pipeline.frameOf();
  for (size_t j = 0; j < record.data.frames.size(); ++j)
  {
    goOn();
    pipeline.writeFrame(frameOf[j], (fs::path(folder) / record.frameImages[j]).string());
  }
  t.set("pictures", watch);
  goOn();
  watch = StageTimings::Stopwatch();
  writeCameraPath(record.result, (fs::path(folder) / "camera-path.vtp").string());
  t.set("camera_path", watch);
  if (options.video)
  {
    goOn();
    if (log)
    {
      *log << "vimlop register: registered video\n";
    }
    watch = StageTimings::Stopwatch();
    writeAfterThePoses("registered video", posesPath,
      [&] { writeRegisteredVideo(record, folder, fps, options.keepGoing); });
    t.set("video", watch);
  }
  if (options.report)
  {
    goOn();
    if (log)
    {
      *log << "vimlop register: report\n";
    }
    watch = StageTimings::Stopwatch();
    writeAfterThePoses("report", posesPath,
      [&]
      {
        // The registration's own model: its search structures are built already.
        RegistrationReport::write(&record, folder, {}, (fs::path(folder) / "report").string(),
          RegistrationReportOptions(), &pipeline.model());
      });
    t.set("report", watch);
  }
  // Last: a folder with a result.json is complete.
  goOn();
  watch = StageTimings::Stopwatch();
  writeRegistrationRecord(record, folder);
  t.set("result_json", watch);
}

nlohmann::json registrationSummaryJson(const VideoRegistrationPipeline& pipeline,
  const RegistrationRecord& record, const std::string& resultPath, double seconds,
  const StageTimings* timings)
{
  const MultiStartResult& outcome = pipeline.outcome();
  const RegistrationResult& result = outcome.best;
  nlohmann::json summary = { { "result", resultPath }, { "frames", record.data.frames.size() },
    { "points", record.data.points.size() }, { "scale", result.sfmToCT.scale },
    { "init", record.confidence ? record.confidence->init : std::string() },
    { "candidates", outcome.candidates.size() }, { "termination", toString(result.termination) },
    { "residual_error_mm", result.residualErrorMm }, { "contour_error_px", result.contourErrorPx },
    { "failure", outcome.failure }, { "failure_reason", outcome.failureReason },
    { "failure_threshold_px", outcome.failureThresholdPx },
    { "failure_residual_mm", outcome.failureResidualMm }, { "runtime_s", seconds } };
  if (timings)
  {
    summary["timings"] = timings->toJson();
    if (const StageTimings::Mark* usable = timings->findMark("result_usable"))
    {
      summary["result_usable_s"] = usable->atWallS;
    }
  }
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
  return summary;
}

std::vector<std::string> registrationSummaryLines(const nlohmann::json& summary)
{
  std::vector<std::string> lines = { formatText(
    "registered %d frames (%d SfM points) from %s (%d candidates) in %.1f s: scale %.4f "
    "mm/unit, residual %.3f mm, contour error %.2f px%s",
    summary.at("frames").get<int>(), summary.at("points").get<int>(),
    summary.at("init").get<std::string>().c_str(), summary.at("candidates").get<int>(),
    summary.at("runtime_s").get<double>(), summary.at("scale").get<double>(),
    summary.at("residual_error_mm").get<double>(), summary.at("contour_error_px").get<double>(),
    summary.at("failure").get<bool>()
      ? (" -- FLAGGED AS A FAILURE: " + summary.at("failure_reason").get<std::string>()).c_str()
      : "") };
  if (summary.contains("camera_position_error_mm"))
  {
    const nlohmann::json& p = summary.at("camera_position_error_mm");
    const nlohmann::json& a = summary.at("camera_angle_error_deg");
    lines.push_back(
      formatText("camera error against the truth: %.3f mm (max %.3f), %.3f deg (max %.3f)",
        p.at("mean").get<double>(), p.at("max").get<double>(), a.at("mean").get<double>(),
        a.at("max").get<double>()));
  }
  return lines;
}

nlohmann::json registrationOptionsJson(const VideoRegistrationOptions& o)
{
  nlohmann::json j = { { "registration", recordjson::optionsJson(o.registration) },
    { "scale_factors", o.multiStart.scaleFactors }, { "canonical_rolls_deg", o.canonical.rollsDeg },
    { "contour_channel", o.contours.channel == ContourChannel::Red ? "red" : "luminance" },
    { "field_stop", o.fieldOfView.toText() } };
#define VIMLOP_VALUE_JSON(Name, Type, member, key, flag, min, max, help) j[key] = o.member;
  VIMLOP_VIDEO_REGISTRATION_VALUES(VIMLOP_VALUE_JSON)
#undef VIMLOP_VALUE_JSON
  return j;
}

} // namespace vimlop
