#ifndef vimlop_RegistrationOutputs_h
#define vimlop_RegistrationOutputs_h

#include <vimlop/Core/FramePose.h>
#include <vimlop/Pipeline/StageTimings.h>
#include <vimlop/Pipeline/VideoRegistrationPipeline.h>
#include <vimlop/Results/RegistrationRecord.h>

#include <nlohmann/json.hpp>

#include <functional>
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

/**
 * @brief The name of the file of registered poses in a result folder,
 * "registered-poses.json": the first file writeRegistrationOutputs() writes.
 */
const char* registeredPosesFileName();

/// @brief What writeRegistrationOutputs() writes beside result.json and the VTK files.
struct RegistrationOutputOptions
{
  /// The registered video: overlays and views per frame, MJPEG (default on).
  bool video = true;
  /// The rendered report in report/ (default on).
  bool report = true;
  /**
   * Called once, with the path of registered-poses.json, as soon as that
   * file is written and before the pictures, video and report (e.g. to tell
   * the user that the result is usable, or to start serving it). Empty: no call.
   */
  std::function<void(const std::string& posesPath)> onResultUsable;
  /**
   * Asked before each part and each frame's picture; false (Ctrl-C) stops the
   * writing with PipelineCancelled. Empty: always go on.
   */
  std::function<bool()> keepGoing;
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
 * @brief Writes the result folder, the usable result first and result.json last:
 * 1. an existing result.json is removed (the folder is incomplete from now on);
 * 2. registered-poses.json (atomically): T and every registered frame's
 *    camera-to-CT pose, with the failure flag (writeRegisteredPoses()); then
 *    `options.onResultUsable` is called;
 * 3. the frames' pictures, camera-path.vtp, the registered video (needs a
 *    display) and the report;
 * 4. the VTK files and result.json (writeRegistrationRecord(), result.json
 *    atomically and last): a folder holding a result.json is complete, one
 *    with registered-poses.json and no result.json is still being written,
 *    or its writing failed.
 * Progress lines go to `log`. When `timings` is given, the time of each part
 * written is set in it, in order: "poses", "pictures" (the frames'),
 * "camera_path", "video", "report", "result_json" (those skipped by
 * `options` absent).
 * @throws vimlop::Error when a file cannot be written; when the video or the
 * report fails, the message says so and that the registered poses are on disk.
 * PipelineCancelled when `options.keepGoing` says stop. `vimlop register`
 * writes into a ResultFolderTransaction's staging folder and commits it after.
 */
void writeRegistrationOutputs(const VideoRegistrationPipeline& pipeline,
  const RegistrationRecord& record, const std::string& folder, double fps,
  const RegistrationOutputOptions& options, std::ostream* log, StageTimings* timings = nullptr);

/**
 * @brief Writes `folder`/registered-poses.json atomically: the format of
 * FramePoseIO.h (each registered frame's "frame_id" and 4 x 4 "camera_to_ct",
 * so `vimlop serve --poses`, `--truth` and readFramePoses() read it) plus
 * "format" "vimlop-registered-poses", "version" 1, "sfm_to_ct" (T, as in
 * result.json's "transform"), "failure", "failure_reason",
 * "failure_threshold_px", "failure_residual_mm", "contour_error_px" and
 * "residual_error_mm".
 * @return the path written.
 * @throws vimlop::Error when the file cannot be written.
 */
std::string writeRegisteredPoses(
  const VideoRegistrationPipeline& pipeline, const std::string& folder);

/**
 * @brief The summary of a finished registration as `vimlop register --json`
 * prints it: counts, scale, errors, failure flag, runtime, and the camera
 * errors against the record's truth when it has one, and the stage
 * timings as "timings" (StageTimings::toJson()) when `timings` is given,
 * with "result_usable_s" when they hold the mark "result_usable".
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
