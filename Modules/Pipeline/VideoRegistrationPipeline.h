#ifndef vimlop_VideoRegistrationPipeline_h
#define vimlop_VideoRegistrationPipeline_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/ContourPoint.h>
#include <vimlop/Core/FramePose.h>
#include <vimlop/Core/MultiStartRegistration.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Pipeline/StageTimings.h>
#include <vimlop/Pipeline/VideoRegistrationInputs.h>
#include <vimlop/Pipeline/VideoRegistrationOptions.h>
#include <vimlop/Results/RegistrationRecord.h>
#include <vimlop/Video/FrameContours.h>
#include <vimlop/Video/SfmReconstruction.h>
#include <vimlop/Video/TrackerTrajectory.h>

#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cv
{
class Mat;
}

namespace vimlop
{

/**
 * @brief The main job as a library: video frames and a CT airway model in,
 * the registered camera poses with their confidence out (DESIGN §2).
 *
 * The stages run in this order, each a public method that checks what it
 * needs from the earlier ones (so an embedding program can replace one, e.g.
 * bring its own model or SfM):
 * 1. loadModel(): the airway surface (a mesh, or the CT's airway segmented);
 * 2. loadFrames(): the frames, checked against the intrinsics and undistorted;
 * 3. detectContours(): the occluding contours of every frame (V1);
 * 4. reconstruct(): structure from motion (built in, or a COLMAP model);
 * 5. estimateInitialScale(): SfM units to mm from the tracker (V14) or given;
 * 6. makeData(): the registration data (V1), see makeVideoRegistrationData;
 * 7. makeStarts(): canonical starts (V13 b) or one manual start (V13 a);
 * 8. run(): the (multi-start) V-IMLOP registration and its failure flag (V13);
 * then record() and writeOutputs() (result folder, registered video, report).
 * `vimlop register`, `vtkVIMLOPVideoRegistration` and Python's
 * `vimlop.register_video` are thin faces over it and share its VideoRegistrationOptions.
 *
 * Progress lines go to the log stream (none by default); warnings to the
 * warning handler (stderr by default); the progress callback may cancel
 * between stages and inside the registration, which then throws
 * PipelineCancelled.
 */
class VideoRegistrationPipeline
{
public:
  /// @brief Progress: the stage ("model", "contours", "sfm", "registration", ...) and the
  /// fraction of it done; return false to cancel.
  using Progress = std::function<bool(const std::string& stage, double fraction)>;

  explicit VideoRegistrationPipeline(
    const VideoRegistrationOptions& options = VideoRegistrationOptions());
  ~VideoRegistrationPipeline();
  VideoRegistrationPipeline(const VideoRegistrationPipeline&) = delete;
  VideoRegistrationPipeline& operator=(const VideoRegistrationPipeline&) = delete;

  const VideoRegistrationOptions& options() const;
  /**
   * @brief Replaces the options of stage 8 (the method, noise model, outlier
   * rejection, ...) for the next run(), keeping the data and the starts:
   * e.g. to compare methods on one sequence, as P5 does.
   * @throws vimlop::Error for invalid options (RegistrationOptions::validate).
   */
  void setRegistrationOptions(const RegistrationOptions& options);

  /// @brief Where progress lines go (nullptr, the default: nowhere).
  void setLog(std::ostream* log);
  /// @brief Who hears warnings (default: "vimlop: warning: ..." on stderr).
  void setWarningHandler(std::function<void(const std::string&)> handler);
  void setProgress(Progress progress);

  ///@{
  /// 1. The airway surface, CT frame (LPS, mm), normals into the air.
  void loadModel(const TriangleMesh& airwayCT);
  /// Reads `meshPath` or, when it is empty, segments the airway of `ctPath`.
  void loadModel(const std::string& meshPath, const std::string& ctPath);
  ///@}

  /**
   * 2. Reads at most `maxFrames` frames of `path` (a folder of pictures or a
   * video file) and undistorts them with `intrinsics` (named
   * `intrinsicsSource` in messages, e.g. its file).
   * @throws vimlop::Error when they cannot be read or the intrinsics are for another size.
   */
  void loadFrames(const std::string& path, const PinholeCamera& intrinsics, int maxFrames = 1000,
    const std::string& intrinsicsSource = "intrinsics");

  /// 3. Occluding contours of every frame (VideoRegistrationOptions::contours).
  void detectContours();
  /**
   * 3, instead: contours detected before (a `vimlop contours` file read with
   * readFrameContours(), named `source` in messages), matched to the loaded
   * frames by name. Points outside the field of view are dropped, as
   * detectContours() drops them.
   * @throws vimlop::Error when a loaded frame has no contours there, the
   * pictures were of another size, or the intrinsics have a lens
   * distortion and the contours were not detected in undistorted frames.
   */
  void useContours(const std::vector<FrameContours>& contours,
    const FrameContoursPictures& pictures, const std::string& source);

  /**
   * 4. Structure from motion of the frames: the built-in one when
   * `colmapFolder` is empty, else that COLMAP sparse model (frames matched by
   * name).
   * @throws vimlop::Error when it registers fewer than 2 frames or 10 points.
   */
  void reconstruct(const std::string& colmapFolder = std::string());
  /**
   * 4, with COLMAP: runs the `colmap` program (`executable`; ColmapRunner)
   * on the loaded frames as the registration sees them (undistorted, written
   * as PNG into a work folder of the system's temporary folder, removed
   * afterwards, kept when COLMAP fails and named in the error), with the
   * intrinsics held fixed, then reads its model as reconstruct() does.
   * COLMAP's features are not masked by a field stop (a warning says so).
   * @throws vimlop::Error when COLMAP is missing or fails, or registers
   * fewer than 2 frames or 10 points.
   */
  void reconstructWithColmap(const std::string& executable = "colmap");

  /**
   * 4, instead: a reconstruction made before (e.g. a `vimlop sfm` file, named
   * `source` in messages), its frames matched to the loaded ones by name.
   * @throws vimlop::Error when it was made with other intrinsics, or holds
   * fewer than 2 of the loaded frames or 10 points.
   */
  void useReconstruction(const SfmReconstruction& sfm, const std::string& source);

  /**
   * 5. The initial scale (V14): from `tracker` over the registered frames
   * (at their own timestamps plus `timeOffsetS`, or, when `fps` is positive
   * or the frames have none, frame f at `timeOffsetS + f / fps` on its clock,
   * with, when `fps` is 0, the video's own rate or else 30: frameTimesS() in
   * VideoInput.h) unless `givenScale`
   * is positive, which then wins (with a warning when the tracker disagrees
   * by more than the scale bound).
   * @throws vimlop::Error when neither is given or the tracker does not overlap the frames.
   */
  void estimateInitialScale(
    const TrackerTrajectory* tracker, double fps, double timeOffsetS, double givenScale);

  /// 6. The registration data (V1) of the registered frames and SfM points.
  void makeData();

  ///@{
  /**
   * 7. The starts. Canonical: one per pose of `posesCT` (those outside the
   * airway are dropped with a warning), or generated along the airway with
   * VideoRegistrationOptions::canonical when null. Manual: the given frame's camera at the
   * given camera-to-CT pose. `source` names the poses in messages (e.g. their file).
   * @throws vimlop::Error when no canonical pose lies inside the airway, or
   * the manual pose is of a frame SfM did not register.
   */
  void makeCanonicalStarts(
    const std::vector<CameraPose>* posesCT = nullptr, const std::string& source = "");
  void makeManualStart(const FramePose& cameraToCT);
  /// Starts given directly (SfM frame to CT frame), e.g. by an embedding program.
  void setStarts(const std::vector<SimilarityTransform>& startsSfmToCT, StartMode mode);
  ///@}

  ///@{
  /**
   * @brief The whole job on `inputs`: prepare() then process().
   * prepare() reads and checks the small files (tracker, start poses), so
   * that a bad one fails before any long work (a program may check more of
   * its own, e.g. a display, between the two); process() runs stages 1-8
   * on the prepared inputs: loads, detects, reconstructs, scales, makes the
   * data and the starts, and registers.
   * @throws vimlop::Error naming the file or stage that failed; PipelineCancelled.
   */
  void run(const VideoRegistrationInputs& inputs);
  void prepare(const VideoRegistrationInputs& inputs);
  void process();
  ///@}

  /**
   * 8. Registers from every start (the multi-start; a single start uses every
   * thread inside the registration instead) and flags the result (V13).
   * @throws vimlop::Error when no candidate could run; PipelineCancelled.
   */
  void run();

  ///@{
  /// What the stages produced (each valid after its stage).
  const TriangleMesh& mesh() const;
  const RegistrationModel& model() const;
  const PinholeCamera& intrinsics() const; ///< as loaded, with its distortion
  int numberOfFrames() const;
  /// The frames' field of view as the stages use it: CV_8U, 255 where
  /// contours and features are taken (inside the field stop, its margin off).
  const cv::Mat& fieldOfViewMask() const;
  const std::vector<std::string>& frameNames() const;
  /// The loaded frames' ids (FrameSequence::ids(): their file numbers).
  const std::vector<int>& frameIds() const;
  /// The CT's DICOM identity (CTVolume::identity) when the model came from one.
  const std::map<std::string, std::string>& ctIdentity() const;
  /**
   * The identity (path, size, SHA-256) of each input file given to prepare(),
   * as they were when it was called (computed in a thread of its own; this
   * waits for it). Empty before prepare(), or when the stages were run one by
   * one. An input that could not be identified has no digest, and a warning
   * says why.
   */
  std::vector<RegistrationRecord::InputFile> inputIdentities() const;
  const std::vector<std::vector<ContourPoint>>& contours() const;
  const SfmReconstruction& sfm() const;
  double initialScale() const;
  const RegistrationData& data() const;
  /// For each data frame, its index in the loaded frames.
  const std::vector<int>& frameOf() const;
  /// Each data frame's time on the video's clock, s, in the order of
  /// data().frames, from the frame rate and offset given to
  /// estimateInitialScale() (empty before it).
  std::vector<double> frameTimesS() const;
  /// Every loaded frame's time on the video's clock, s, in the order of
  /// frameIds() (empty before estimateInitialScale()).
  const std::vector<double>& loadedFrameTimesS() const;
  /**
   * The rate the frames were taken at, frames per second (for the registered
   * video): the rate given to estimateInitialScale() when positive, else the
   * rate the frames' file records, else 30 (framesPerSecondOf()).
   */
  double framesPerSecond() const;
  const std::vector<SimilarityTransform>& starts() const;
  StartMode startMode() const;
  /// For canonical starts: the id of the frame placed at each pose.
  int anchorFrameId() const;
  const MultiStartResult& outcome() const;
  /// The winner's result (outcome().best).
  const RegistrationResult& result() const;
  bool flaggedAsFailure() const;
  ///@}

  /**
   * @brief The wall and CPU time of each stage run so far, in the order they
   * ran: "frames", "model" (reading the mesh or segmenting the CT
   * included), "contours", "sfm", "scale", "data", "starts" (not for starts
   * given with setStarts()), then run()'s: "screening" and "final" for a
   * multi-start ("screening" only when it screened), "registration" for a
   * single start. A stage run again replaces its time; a stage not run is
   * absent.
   */
  const StageTimings& timings() const;

  /**
   * @brief Writes frame `index` (of the loaded, undistorted frames) as a
   * picture file (PNG by the name's extension).
   * @throws vimlop::Error when it cannot be written.
   */
  void writeFrame(int index, const std::string& path) const;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

/// @brief Thrown when the progress callback asked the pipeline to stop.
struct PipelineCancelled
{
};

} // namespace vimlop

#endif
