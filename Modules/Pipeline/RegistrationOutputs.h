#ifndef vimlop_RegistrationOutputs_h
#define vimlop_RegistrationOutputs_h

#include <vimlop/Core/FramePose.h>
#include <vimlop/Pipeline/StageTimings.h>
#include <vimlop/Pipeline/VideoRegistrationPipeline.h>
#include <vimlop/Results/RegistrationRecord.h>

#include <nlohmann/json.hpp>

#include <iosfwd>
#include <string>
#include <vector>

/**
 * @file RegistrationOutputs.h
 * @brief The last stages of the main job: the record of a finished
 * VideoRegistrationPipeline and the result folder written from it.
 */
namespace vimlop
{

/// @brief What writeRegistrationOutputs() writes beside result.json and the VTK files.
struct RegistrationOutputOptions
{
  /// The registered video: overlays and views per frame, MJPEG (default on).
  bool video = true;
  /// The rendered report in report/ (default on).
  bool report = true;
};

/**
 * @brief The record (RegistrationRecord) of a finished pipeline: model, data,
 * options, winner's start and result, confidence (V13) and, when
 * `truthPoses` is not empty, the ground truth of the registered frames
 * (`truthSource` names them in messages). Frame pictures are named
 * frames/frame-NNNN.png, written by writeRegistrationOutputs().
 * @throws vimlop::Error when the truth lacks a registered frame.
 */
RegistrationRecord makeRegistrationRecord(const VideoRegistrationPipeline& pipeline,
  const std::string& source, const std::vector<FramePose>& truthPoses = {},
  const std::string& truthSource = "the truth");

/**
 * @brief Writes the result folder: the frames' pictures, the registered
 * video (needs a display), camera-path.vtp, result.json (last, so that a
 * folder holding one is complete; see RegistrationRecordIO.h) and the report.
 * An existing result.json is removed first. Progress lines go to `log`.
 * When `timings` is given, the time of each part written is set in it, in
 * order: "pictures" (the frames'), "video", "camera_path", "result_json",
 * "report" (those skipped by `options` absent).
 * @throws vimlop::Error when a file cannot be written.
 */
void writeRegistrationOutputs(const VideoRegistrationPipeline& pipeline,
  const RegistrationRecord& record, const std::string& folder, double fps,
  const RegistrationOutputOptions& options, std::ostream* log, StageTimings* timings = nullptr);

/**
 * @brief The summary of a finished registration as `vimlop register --json`
 * prints it: counts, scale, errors, failure flag, runtime, and the camera
 * errors against the record's truth when it has one, and the stage
 * timings as "timings" (StageTimings::toJson()) when `timings` is given.
 */
nlohmann::json registrationSummaryJson(const VideoRegistrationPipeline& pipeline,
  const RegistrationRecord& record, const std::string& resultPath, double seconds,
  const StageTimings* timings = nullptr);

/**
 * @brief registrationSummaryJson() as the lines `vimlop register` prints:
 * frames, candidates, runtime, scale, errors and the failure flag, then the
 * camera errors against the truth when the summary has them.
 */
std::vector<std::string> registrationSummaryLines(const nlohmann::json& summary);

/**
 * @brief Every setting of the pipeline as JSON (the registration options in
 * the layout of result.json's "options", then the pipeline's own), so that
 * the faces can show, and a test compare, the defaults they use.
 */
nlohmann::json registrationOptionsJson(const VideoRegistrationOptions& options);

} // namespace vimlop

#endif
