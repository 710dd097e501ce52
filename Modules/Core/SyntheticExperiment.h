#ifndef vimlop_SyntheticExperiment_h
#define vimlop_SyntheticExperiment_h

#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Core/SimilarityTransform.h>

#include <cstdint>
#include <vector>

namespace vimlop
{

/**
 * @brief Parameters of the paper's synthetic experiment (P1, DESIGN section 6):
 * the paper's values by default.
 */
struct SyntheticOptions
{
  int cameras = 6;
  int points = 900;
  /// SfM point noise std along and across the observing camera's optical axis, mm.
  double sigmaAlongMm = 0.5;
  double sigmaAcrossMm = 0.3;
  /// Camera pose noise: translation and rotation magnitudes uniform in [0, max], mm and degrees.
  double poseNoiseMaxMm = 0.25;
  double poseNoiseMaxDeg = 0.25;
  /// Misalignment of the data: rotation and translation magnitudes uniform in these ranges.
  double misalignMinMm = 2.0;
  double misalignMaxMm = 3.0;
  double misalignMinDeg = 2.0;
  double misalignMaxDeg = 3.0;
  /// The endoscope: 320 x 240 pixels, fx = fy = 200 (a 77° x 62° field of view).
  PinholeCamera intrinsics = PinholeCamera::simulatedEndoscope();
  /// Spacing of the cameras along their path, mm (default 0.75).
  double cameraStepMm = 1.5;
  /// Least distance of every camera to the wall, mm (default 2: the radius of a 4 mm endoscope).
  double minClearanceMm = 2.0;
  /// Spacing of the simulated video contour points along the true contours, pixels (default 3).
  double contourSpacingPx = 3.0;
  /// Gaussian noise on video contour positions, std per axis, pixels
  /// (default 0: the contours are the model's at the true poses; the paper's
  /// P1 draws it from Σ2d = 9 px², 3 px, see paper()).
  double contourNoisePx = 0.0;
  /// Noise on video contour normals: the normal turned by an angle drawn from
  /// a von Mises distribution of this concentration, drawn as a normal of std
  /// 1/sqrt(κ), which it matches within 1 % for κ above 50 (default 0: none;
  /// the paper's P1: 200, an angle std of 4.1 degrees).
  double contourNormalKappa = 0.0;
  /// A wrong start scale: the registration starts from a scale (1 + this)
  /// times the true one, about the mean camera centre so that the cameras
  /// stay in the airway (default 0: the true scale, as the paper). Finite
  /// and above -1; VIMLOP recovers it within its scale bounds (P1: 0.8 to 1.25).
  double startScaleError = 0.0;

  /// @brief The paper's synthetic data (Sec. 3): these defaults with its
  /// contour noise, Σ2d = 9 px² (3 px per axis) and κ = 200.
  static SyntheticOptions paper();
};

/// @brief One synthetic trial: data in a misaligned SfM frame and its ground truth.
struct SyntheticTrial
{
  RegistrationData data;
  /// T_gt: the SfM frame (misaligned data) to CT.
  SimilarityTransform truthSfmToCT;
  /// The start of the registration: identity (the misalignment is in the data).
  SimilarityTransform initialSfmToCT;
  std::vector<CameraPose> trueCamerasCT;
  /// Centres of the faces visible to the middle camera at its true pose (TRE targets).
  std::vector<Eigen::Vector3d> targetsCT;
};

/**
 * @brief Builds one P1 trial on `model`, reproducibly from `seed`: the data
 * drawn from the model itself (makeSyntheticTrial(model, model, ...)).
 */
SyntheticTrial makeSyntheticTrial(
  const RegistrationModel& model, const SyntheticOptions& options, std::uint64_t seed);

/**
 * @brief Builds one P1 trial whose data are drawn from `dataSurface`, a
 * surface in the model's frame other than the model (a finer or otherwise
 * segmented one, a deformed one: a model error), reproducibly from `seed`.
 *
 * Cameras lie on a straight path inside the cavity (every one at least
 * `minClearanceMm` from the wall), looking roughly along it; points are drawn
 * uniformly over the surface area visible to them and get view-aligned noise
 * from the camera that sees them; camera poses get uniform noise; video
 * contours are the visible occluding contours at the true poses. The data is
 * then misaligned by a random rigid motion about its centroid, drawn again
 * until every camera still starts inside the airway (V-IMLOP's anatomical
 * constraint needs a start inside).
 *
 * The cameras move, the points lie and the contours are seen in
 * `dataSurface` (the anatomy as it is); the cameras keep their clearance in
 * `model` too (V-IMLOP's anatomical constraint holds the true cameras inside
 * the model); the TRE targets and the start's check that the cameras are
 * inside use `model` (what the registration has).
 * With `dataSurface` the model (or the same surface), the trial is the one
 * of makeSyntheticTrial(model, options, seed), bit for bit.
 *
 * @throws vimlop::Error for invalid options or if no camera path with enough
 * view can be found.
 */
SyntheticTrial makeSyntheticTrial(const RegistrationModel& model,
  const RegistrationModel& dataSurface, const SyntheticOptions& options, std::uint64_t seed);

} // namespace vimlop

#endif
