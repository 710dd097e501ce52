#ifndef vimlop_EndoscopeSimulation_h
#define vimlop_EndoscopeSimulation_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/DepthMap.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Evaluation/EvaluationProgress.h>
#include <vimlop/Rendering/EndoscopeTrajectory.h>
#include <vimlop/Video/TrackerTrajectory.h>

#include <opencv2/core/mat.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief Settings of a simulated endoscope sequence (the virtual endoscope of P2).
struct EndoscopeSimulationOptions
{
  /// Number of frames (default 30).
  int frames = 30;
  /// Seed of the path, the texture, the picture noise and the tracker noise (default 1).
  std::uint64_t seed = 1;
  /// The endoscope camera (default 320 x 240 pixels, fx = fy = 200: 77° x 62°).
  PinholeCamera intrinsics = PinholeCamera::simulatedEndoscope();
  /// The path: frames, step, clearance, sway (frames and intrinsics are set from above).
  EndoscopeTrajectoryOptions trajectory;
  /// Video frame rate, frames per second (default 30).
  double framesPerSecond = 30.0;
  /// Simulated electromagnetic tracker: rate (default 40 Hz), position noise
  /// std (default 0.2 mm) and how long it records before the first and after
  /// the last frame (default 0.3 s).
  double trackerRateHz = 40.0;
  double trackerNoiseMm = 0.2;
  double trackerMarginS = 0.3;
  /// Picture blur and noise (see vtkVIMLOPVirtualEndoscope).
  /// Defaults 0.5 px and 1.5 grey levels.
  double blurSigmaPx = 0.5;
  double noiseSigma = 1.5;
};

/// @brief A simulated sequence and its ground truth.
struct SimulatedVideo
{
  PinholeCamera intrinsics;
  std::vector<CameraPose> camerasCT; ///< true camera-to-CT poses
  std::vector<double> frameTimesS;
  std::vector<std::string> names; ///< frame file names
  std::vector<cv::Mat> frames;    ///< 8-bit BGR
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
 * @throws vimlop::Error if no path fits in the airway, or on cancellation.
 */
SimulatedVideo simulateEndoscopeVideo(const RegistrationModel& model,
  const EndoscopeSimulationOptions& options, const EvaluationProgress& progress);

/**
 * @brief Writes a simulated sequence to `folder`: `frames/frame000.png`, ...;
 * `depth/frame000.tiff`, ... (32-bit float camera depth in mm, 0 where no
 * surface is seen); `intrinsics.yaml`; `poses.json` (per frame: name, time,
 * true camera-to-CT 4x4 matrix, row-major); `tracker.csv`.
 * @throws vimlop::Error if the folder cannot be written.
 */
void writeSimulatedVideo(const SimulatedVideo& video, const std::string& folder);

} // namespace vimlop

#endif
