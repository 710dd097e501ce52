#ifndef vimlop_EndoscopeSimulation_h
#define vimlop_EndoscopeSimulation_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/DepthMap.h>
#include <vimlop/Core/PathReplay.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Evaluation/EvaluationProgress.h>
#include <vimlop/Evaluation/FieldStop.h>
#include <vimlop/Evaluation/VideoArtifacts.h>
#include <vimlop/Rendering/EndoscopeTrajectory.h>
#include <vimlop/Video/TrackerTrajectory.h>

#include <opencv2/core/mat.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief Settings of a simulated endoscope sequence (the virtual endoscope of P2).
 *
 * The error sources of a realistic world (issue 14) are named knobs, each off
 * by default so that the default sequence is the ideal world of P1–P3, bit
 * for bit: the field stop and vignetting (`fieldStop`), lens distortion
 * (`intrinsics.distortion`, radial-tangential or fisheye by
 * `intrinsics.lensModel`), calibration error of the intrinsics given to the
 * user (`calibrationFocalErrorRelative`, `calibrationPrincipalPointErrorPx`,
 * `calibrationDistortionErrorRelative`),
 * tracker latency and clock offset (`trackerLatencyS`,
 * `trackerClockOffsetS`), the video artifacts (`artifacts`: motion blur,
 * specular highlights, exposure, shot noise, compression, occluders) and the
 * hand's tremor (`trajectory.jitterMm`, `trajectory.jitterDeg`). The path's
 * own settings (its step, roll, turn) are not errors and leave the world ideal.
 * Realistic values and their sources:
 * Documentation/Simulation.md.
 */
struct EndoscopeSimulationOptions
{
  /// Number of frames (default 30).
  int frames = 30;
  /// Seed of the path, the texture, the picture and tracker noise and the occluders (default 1).
  std::uint64_t seed = 1;
  /// The true endoscope camera (default 320 x 240 pixels, fx = fy = 200: 77°
  /// x 62°). Its distortion coefficients (OpenCV's k1, k2, p1, p2[, k3], or
  /// with `lensModel` Fisheye the fisheye's k1, k2, k3, k4) are rendered into
  /// the frames (default none; wide-angle rigid endoscopes: k1 about -0.3 to
  /// -0.4, Documentation/Simulation.md).
  PinholeCamera intrinsics = PinholeCamera::simulatedEndoscope();
  /// Calibration error: the intrinsics given to the user (intrinsics.yaml)
  /// have focal lengths (1 + this) times the true ones (default 0; a
  /// checkerboard calibration of an endoscope: about 1 %, an estimate from
  /// Documentation/Simulation.md). In (-0.5, 0.5).
  double calibrationFocalErrorRelative = 0.0;
  /// Calibration error: the intrinsics given to the user have distortion
  /// coefficients (1 + this) times the true ones, every coefficient alike
  /// (default 0; a checkerboard calibration of a wide-angle lens misjudges
  /// k1 by a few %: about 3 %, an estimate from Documentation/Simulation.md).
  /// In (-1, 1), so that the given lens bends the same way as the true one.
  /// Acts only with a lens (intrinsics.distortion).
  double calibrationDistortionErrorRelative = 0.0;
  /// Calibration error: the given principal point minus the true one, pixels
  /// (default (0, 0); a few pixels, Documentation/Simulation.md).
  Eigen::Vector2d calibrationPrincipalPointErrorPx = Eigen::Vector2d::Zero();
  /// The endoscope's image circle and vignetting (default none).
  FieldStopOptions fieldStop;
  /// Long sequences (issue 16): with `replay.pathFrames` > 0, a path of that
  /// many poses is made and the `frames` frames are played along it forward
  /// and back, with pauses and fast moves (PathReplay.h; drawn from `seed`).
  /// Default off: the path has one pose per frame.
  PathReplayOptions replay;
  /// The path: frames, step, clearance, sway, tremor, turn (frames and
  /// intrinsics are set from above).
  EndoscopeTrajectoryOptions trajectory;
  /// Video frame rate, frames per second (default 30).
  double framesPerSecond = 30.0;
  /// Simulated electromagnetic tracker: rate (default 40 Hz), position noise
  /// std (default 0.2 mm) and how long it records before the first and after
  /// the last frame (default 0.3 s).
  double trackerRateHz = 40.0;
  double trackerNoiseMm = 0.2;
  double trackerMarginS = 0.3;
  /// The simulated tracker is a 6-DOF sensor: it records the camera's
  /// rotation too, as the sensor's (default off: positions only, as a 5-DOF
  /// sensor's position or a CSV of tips). The sensor is taken to be
  /// calibrated to the camera exactly (no hand-eye error).
  bool trackerRotation = false;
  /// Its rotation noise: each sample turned about a random axis by an angle
  /// whose components are Gaussian with this std per axis, degrees (default
  /// 0.3: an estimate, 6-DOF electromagnetic sensors are specified at a few
  /// tenths of a degree RMS in a clean field, Documentation/Simulation.md).
  /// At least 0.
  double trackerRotationNoiseDeg = 0.3;
  /// A fixed error of the tracker in the CT frame, as a navigation system
  /// leaves one: every tip shifted by this length in one random direction
  /// (the registration of the tracker to the patient, mm; default 0: an
  /// exact registration; about 1 mm clinically, Documentation/Simulation.md)
  /// and, with trackerRotation, every rotation turned by this angle about
  /// one random axis (that registration's rotation and the sensor's
  /// calibration to the camera, degrees; default 0; about 1). Both drawn
  /// from `seed`; at least 0.
  double trackerPositionBiasMm = 0.0;
  double trackerRotationBiasDeg = 0.0;
  /// Tracker latency, s: each sample reports where the tip was this long
  /// before its time stamp (default 0; electromagnetic trackers: tens of ms,
  /// Documentation/Simulation.md). At least 0.
  double trackerLatencyS = 0.0;
  /// The tracker's clock minus the video's, s: a sample stamped t was taken
  /// at video time t - offset (default 0; unsynchronised clocks: tens to
  /// hundreds of ms, an estimate). In the recorded trajectory it adds to the
  /// latency; they are apart because a system may know one and not the other.
  double trackerClockOffsetS = 0.0;
  /// Picture blur and noise (see vtkVIMLOPVirtualEndoscope).
  /// Defaults 0.5 px and 1.5 grey levels.
  double blurSigmaPx = 0.5;
  double noiseSigma = 1.5;
  /// The artifacts of real endoscope video (default none).
  VideoArtifactOptions artifacts;

  /// @brief True when every error source of the realistic world is off (the
  /// defaults); the path's step, roll and turn do not count.
  bool isIdealWorld() const;

  /**
   * @brief Checks the settings.
   * @throws vimlop::Error naming the first problem: fewer than 2 frames,
   * invalid intrinsics or field stop, non-finite or out-of-range distortion,
   * calibration error, tracker rate, latency or clock offset, video
   * artifacts, the path's options (EndoscopeTrajectoryOptions::validate()).
   */
  void validate() const;
};

/// @brief A simulated sequence and its ground truth.
struct SimulatedVideo
{
  PinholeCamera intrinsics; ///< the true intrinsics the frames are rendered with
  /// The intrinsics a user is given (as calibrated: the true ones with the
  /// options' calibration error).
  PinholeCamera calibratedIntrinsics;
  std::vector<CameraPose> camerasCT; ///< true camera-to-CT poses
  std::vector<double> frameTimesS;
  std::vector<std::string> names; ///< frame file names
  std::vector<cv::Mat> frames;    ///< 8-bit BGR
  /// Per frame, the camera z of the surface seen at each pixel of the frame
  /// as rendered (through the lens distortion when there is one; the field
  /// stop hides no depth).
  std::vector<DepthMap> depth;
  TrackerTrajectory tracker; ///< tracked tip positions, in the CT frame (mm)

  /// @brief Length of the camera path: the distances between successive optical centres, mm.
  double pathLengthMm() const;
  /// @brief The least distance of an optical centre to the surface of `model`, mm
  /// (infinite with no cameras).
  double leastWallDistanceMm(const RegistrationModel& model) const;
};

/**
 * @brief Simulates an endoscope sequence in the airway of `model`: a path
 * (makeEndoscopeTrajectory), the frames and depth maps of the virtual
 * endoscope (vtkVIMLOPVirtualEndoscope with a MucosaTexture seeded from
 * `seed`), and a noisy tracker recording of the tip. Counts the frames to
 * `progress` as "simulate: frame". Needs an X display.
 *
 * With lens distortion or a field stop, each frame is rendered without noise
 * by a pinhole camera that covers the distorted field (pinholeCameraCovering),
 * distorted (renderLensDistortion), multiplied by the field stop's gain, and
 * only then given the sensor noise (so that the black border is noisy, as a
 * real sensor's is). Without them, the renderer's own noise is kept, as before.
 *
 * The video artifacts (VideoArtifacts.h) act in the order of the light's
 * path: motion blur and specular highlights on the pinhole render (with its
 * depth map and the poses of the exposure), then the lens, the occluders on
 * the lens window, the field stop, the exposure's gain and clipping, the sensor's
 * noise (Gaussian and shot), and last the compression of the whole sequence.
 * The depth maps stay the geometry's: neither blurred nor occluded.
 * @throws vimlop::Error for invalid options (validate()), if no path fits in
 * the airway, or on cancellation.
 */
SimulatedVideo simulateEndoscopeVideo(const RegistrationModel& model,
  const EndoscopeSimulationOptions& options, const EvaluationProgress& progress);

/**
 * @brief The simulated tracker's recording of the optical centres of
 * `camerasCT` (frame f at time f / framesPerSecond): samples at
 * trackerRateHz from trackerMarginS before the first frame to as long after
 * the last, stamped on the tracker's clock, each the tip where it was at
 * video time (stamp - trackerClockOffsetS - trackerLatencyS), linear between
 * frames and extrapolated at constant velocity beyond them, plus Gaussian
 * noise of trackerNoiseMm per axis (seeded from `seed`). With
 * trackerRotation, each sample has the camera's rotation at that time too
 * (interpolated along the shorter arc between frames, held beyond them),
 * turned by a random rotation vector with trackerRotationNoiseDeg per axis.
 * Every sample carries the same bias: trackerPositionBiasMm and
 * trackerRotationBiasDeg, in directions drawn from `seed`.
 */
TrackerTrajectory simulateTrackerRecording(
  const std::vector<CameraPose>& camerasCT, const EndoscopeSimulationOptions& options);

/**
 * @brief Writes a simulated sequence to `folder`: what a user has,
 * `frames/frame000.png`, ..., `intrinsics.yaml` (the calibrated intrinsics,
 * with the distortion coefficients) and `tracker.csv`; and the truth a user
 * would not have, apart under `truth/`: `poses.json` (per frame: name, time,
 * true camera-to-CT 4x4 matrix, row-major), `depth/frame000.tiff`, ...
 * (32-bit float camera depth in mm, 0 where no surface is seen) and
 * `intrinsics.yaml` (the true intrinsics).
 * @throws vimlop::Error if the folder cannot be written.
 */
void writeSimulatedVideo(const SimulatedVideo& video, const std::string& folder);

} // namespace vimlop

#endif
