#ifndef vimlop_RegistrationRecord_h
#define vimlop_RegistrationRecord_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/RegistrationResult.h>
#include <vimlop/Core/SimilarityTransform.h>
#include <vimlop/Core/TriangleMesh.h>

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief Everything about one registration run: the model and the data it
 * registered, the options, the start, the result, and the ground truth when
 * the data were simulated. What a result folder holds (see
 * RegistrationRecordIO.h) and what `vimlop report` draws.
 */
struct RegistrationRecord
{
  /// The truth of simulated data (P1, P2).
  struct GroundTruth
  {
    /// The true T, SfM frame to CT frame.
    SimilarityTransform sfmToCT;
    /// The true camera of every frame, CT frame, in the order of the frames.
    std::vector<CameraPose> camerasCT;
    /// Points for the target registration error, CT frame, mm (may be empty).
    std::vector<Eigen::Vector3d> targetsCT;
  };

  /// What produced the run, for people (e.g. "vimlop evaluate synthetic, seed 1, trial 0").
  std::string source;
  /// The model surface (CT frame, mm, normals into the air).
  TriangleMesh model;
  RegistrationData data;
  RegistrationOptions options;
  /// The start, SfM frame to CT frame.
  SimilarityTransform initialSfmToCT;
  RegistrationResult result;
  /// Per frame (in the order of data.frames), the picture of the frame: a PNG
  /// path relative to the result folder, or empty when there is none.
  std::vector<std::string> frameImages;
  /// Per frame (in the order of data.frames), the name of the file (or the
  /// frame of a video) it came from, e.g. "frame011.png"; may be empty.
  std::vector<std::string> frameSources;
  /// Per frame (in the order of data.frames), its time on the video's clock,
  /// s (from the video, or --fps and --time-offset for a frame folder),
  /// written as "time_s"; empty when unknown.
  std::vector<double> frameTimesS;
  /// A frame that was read but got no pose (SfM did not register it): a
  /// moment the scope was not tracked.
  struct FrameWithoutPose
  {
    int frameId = 0;
    /// The file (or video frame) it came from.
    std::string source;
    /// Its time on the video's clock, s; NaN when unknown.
    double timeS = std::numeric_limits<double>::quiet_NaN();
  };
  /// In video order; written as "frames_without_pose" ("id", "source", "time_s").
  std::vector<FrameWithoutPose> framesWithoutPose;
  /// One input of the run, identified: what it is for ("ct", "frames",
  /// "intrinsics", ...), its path as given, its size in bytes and its SHA-256
  /// (of a folder: of its files' names and bytes, in name order).
  struct InputFile
  {
    std::string role;
    std::string path;
    std::uint64_t bytes = 0;
    std::string sha256;
  };
  std::vector<InputFile> inputs;
  /// Who and what the CT is, from its DICOM headers when it has them:
  /// "series_instance_uid", "study_instance_uid", "patient_id".
  std::map<std::string, std::string> ctIdentity;
  std::optional<GroundTruth> truth;
  /// How much to trust the result (V13): written as "confidence".
  struct Confidence
  {
    /// True when the contour error or the 3-D residual exceeds its threshold
    /// (or too few contour points matched): do not navigate with it.
    bool failure = false;
    double failureThresholdPx = 0.0;
    /// Why the result is flagged, for people (empty when it is not); written as "failure_reason".
    std::string reason;
    /// How the start was found: "manual", "canonical", "perturbed", ...
    std::string init;
    /// Candidates of a multi-start (1 for a single start) and the winner's index.
    int candidates = 1;
    int winner = 0;
    /// The threshold on the 3-D residual, mm; 0 when the check had none (a
    /// record from before it). Written as "failure_residual_mm".
    double failureResidualMm = 0.0;
  };
  std::optional<Confidence> confidence;
  /// The command that ran the registration, as a shell reads it (each word
  /// quoted where it needs to be), to show it and to run it again; empty when
  /// the run did not come from a command line. Written as "command_line".
  std::string commandLine;
  /// Wall time of the whole run from its start until the result was found
  /// (loading, SfM, contours, the multi-start), s; the outputs written after
  /// it are not in it (result.runtimeSeconds is the winning start's alone).
  /// 0 when unknown. Written as "run_wall_s".
  double runWallS = 0.0;
  /// Versions of the libraries and inputs worth recording (name -> text),
  /// written as "versions" next to VIMLOP's own.
  std::map<std::string, std::string> versions;
};

} // namespace vimlop

#endif
