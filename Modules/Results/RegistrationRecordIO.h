#ifndef vimlop_RegistrationRecordIO_h
#define vimlop_RegistrationRecordIO_h

#include <vimlop/Results/RegistrationRecord.h>

#include <string>

/**
 * @file RegistrationRecordIO.h
 * @brief The result folder of a registration: what `vimlop evaluate synthetic
 * --save-trial` (and `vimlop register`) write and `vimlop report` reads.
 *
 * A result folder holds (VTK XML files in the layouts of
 * RegistrationInputConversion.h and RegistrationOutputConversion.h, so that
 * readers can feed a vtkVIMLOPRegistration from it):
 *
 * | file                  | content                                              |
 * |-----------------------|------------------------------------------------------|
 * | `result.json`         | the summary below, written last (atomically)          |
 * | `model.vtp`           | model surface, CT frame, mm, "Normals" into the air   |
 * | `sfm-points.vtp`      | SfM points with "Covariance", SfM frame               |
 * | `frame-table.vtt`     | intrinsics and SfM-frame pose of every frame          |
 * | `video-contours.vtp`  | video contour points of every frame, pixels           |
 * | `registered-points.vtp` | SfM points in CT with "Inlier", "MatchedModelPoint" |
 * | `camera-poses.vtt`    | camera-to-CT pose and contour metrics of every frame  |
 * | `correspondences.vtp` | matched video/model contour pairs, pixels             |
 * | `targets.vtp`         | ground-truth target points, CT frame (optional)       |
 * | `frames/frame-<id>.png` | the frames' pictures (optional)                     |
 *
 * `vimlop register` (writeRegistrationOutputs() in Pipeline) also writes
 * `registered-poses.json` first, as soon as the registration ends, and this
 * module's files, result.json last, after its video and report: there too a
 * folder with a result.json is complete.
 *
 * `result.json` (format "vimlop-result", version 1) holds: "source",
 * "vimlop_version", "method", "parameters" (every RegistrationOptions field,
 * in its units: mm, px, degrees where named so), "initial_transform" and
 * "transform" (each {"matrix" 4 x 4 row lists, "scale", "rotation" 3 x 3,
 * "translation" mm, "rotation_angle_deg"}), "termination", "iterations",
 * "runtime_s", "residual_error_mm", "contour_error_px",
 * "contour_error_inliers_px", "points" (count, inliers), "frames" (per frame:
 * "id", "intrinsics" {fx, fy, cx, cy, width_px, height_px}, "camera_to_sfm"
 * and "camera_to_ct" 4 x 4, "contour_points", "matched", "inliers",
 * "contour_error_px", "contour_error_inliers_px", "visible_model_samples",
 * "image", and "source": the frame's file), "history" (per iteration: "iteration", "with_contours",
 * "transform" and "updated" 4 x 4, "cost", "cost_3d", "cost_2d",
 * "point_inliers", "contour_matches", "contour_inliers", "residual_error_mm",
 * "contour_error_px", "backoff_steps", "acceleration", "extrapolation_undone",
 * "times_ms" per stage), "files" (the table above) and, for simulated data,
 * "ground_truth" ("transform", "cameras_ct" 4 x 4 each, "targets_file",
 * "tre_mm", per-frame "camera_position_error_mm" and "camera_angle_error_deg");
 * when known, "inputs" (per input file: "role", "path", "bytes", "sha256")
 * and "ct_identity" (the CT's DICOM series and study instance UIDs and
 * patient id).
 * Readers ignore keys they do not know, so later writers may add some.
 */

namespace vimlop
{

/// @brief Where a result folder keeps the picture of frame `frameId`, relative
/// to the folder: "frames/frame-0011.png" (the writers of frameImages use it).
std::string resultFrameImageName(int frameId);

/// @brief The "format" value of result.json.
const char* resultFormatName();

/// @brief The "version" value of result.json this build writes and reads.
int resultFormatVersion();

/**
 * @brief Writes `record` into the folder `folder` (created if needed; files
 * of the same names are replaced). The frame pictures named by
 * record.frameImages must already be there. result.json is written last,
 * through a temporary file and a rename, so a folder with a result.json is
 * complete.
 * @throws vimlop::Error if a file cannot be written.
 */
void writeRegistrationRecord(const RegistrationRecord& record, const std::string& folder);

/**
 * @brief Reads a result folder written by writeRegistrationRecord().
 * @throws vimlop::Error "'folder': ..." for a missing folder or a file, a folder
 * without result.json ("not a VIMLOP result folder"), a result.json of
 * another format or a newer version, or a missing or malformed file.
 */
RegistrationRecord readRegistrationRecord(const std::string& folder);

} // namespace vimlop

#endif
