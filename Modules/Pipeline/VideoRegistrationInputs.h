#ifndef vimlop_VideoRegistrationInputs_h
#define vimlop_VideoRegistrationInputs_h

#include <string>

namespace vimlop
{

/// @brief Where the registration starts (V13).
enum class StartMode
{
  Manual,   ///< the camera-to-CT pose of one frame, given by the user (V13 a)
  Canonical ///< every canonical pose along the airway, a multi-start (V13 b)
};

/**
 * @brief The inputs of the main job as files, what `vimlop register` and
 * vtkVIMLOPVideoRegistration take (see VideoRegistrationPipeline::run()).
 */
struct VideoRegistrationInputs
{
  /// The model: an airway mesh (CT frame, normals into the air) or, when it
  /// is empty, a CT volume whose airway is segmented.
  std::string meshPath;
  std::string ctPath;
  /// The video: a folder of pictures, a video file or a tracked sequence
  /// (PLUS/Slicer `.igs.mha`, `.igs.nrrd`, `.seq.nrrd`, with its
  /// timestamps), at most `maxFrames` of
  /// it (default 1000), and its intrinsics (OpenCV YAML/JSON/XML).
  std::string framesPath;
  int maxFrames = 1000;
  std::string intrinsicsPath;
  /// Structure from motion: empty for the built-in one, else a COLMAP sparse model folder.
  std::string colmapFolder;
  /// Or a reconstruction already made: a `vimlop sfm` file (frames matched by name).
  std::string sfmFile;
  /// Or COLMAP run here on the frames (VideoRegistrationPipeline::reconstructWithColmap).
  bool runColmap = false;
  /// The COLMAP program that runColmap runs (default "colmap", on the PATH).
  std::string colmapExecutable = "colmap";
  /// Contours already detected: a `vimlop contours` file (frames matched by
  /// name), instead of detecting them (V1).
  std::string contoursFile;
  /// V14: the tracker (a CSV, or a tracked sequence with `trackerTransform`),
  /// or the initial scale in mm per SfM unit (wins when positive).
  std::string trackerPath;
  /// The transform of a tracked sequence that carries the scope (e.g.
  /// "ProbeToTracker"): read from `trackerPath`, or from the frames' own file
  /// when `trackerPath` is empty. Empty: the tracker is a CSV.
  std::string trackerTransform;
  /// The tracker registered to the patient, as 3D Slicer saves its
  /// tracker-to-RAS transform (an ITK transform file, read by
  /// intoLpsFromSlicerFile() in CoordinateFrames.h); empty: none. It needs
  /// a 6-DOF sensor's rotation, in the camera's frame (x right, y down, z
  /// forward): a tracked sequence's transform or a CSV with `qw,qx,qy,qz`.
  /// The tracked camera pose turns the canonical starts (turnedAsTracked()
  /// in CanonicalStarts.h): a rotation prior.
  std::string trackerToCTPath;
  double initialScale = 0.0;
  /// Frame times on the tracker's clock: the frames' own timestamps (a
  /// tracked sequence) plus `timeOffsetS`, or their video's rate; a positive
  /// `framesPerSecond` overrides either, and a folder's frames are 30 fps
  /// apart unless it is given (frameTimesS() in VideoInput.h).
  double framesPerSecond = 0.0;
  double timeOffsetS = 0.0;
  /// V13: canonical starts (generated along the airway, or the poses of
  /// `startPosesPath`), or a manual start (the first pose of `startPosesPath`).
  StartMode startMode = StartMode::Canonical;
  std::string startPosesPath;

  /**
   * @brief Sets the start from its text form: "canonical" (generated along
   * the airway), "canonical:POSES.json" or "manual:POSE.json".
   * @throws vimlop::Error naming `what` (e.g. the flag) for any other text.
   */
  void setStart(const std::string& text, const std::string& what);
  /**
   * @brief Sets the structure from motion from its text form: "builtin",
   * "colmap" (COLMAP run on the frames), "colmap:DIR" (a COLMAP sparse
   * model folder) or the path of a `vimlop sfm` file (ending in .json).
   * @throws vimlop::Error naming `what` for any other text.
   */
  void setStructureFromMotion(const std::string& text, const std::string& what);
};

} // namespace vimlop

#endif
