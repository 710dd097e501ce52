#ifndef vimlop_VideoEvaluation_h
#define vimlop_VideoEvaluation_h

#include "CanonicalPoses.h"
#include "EndoscopeSimulation.h"
#include "MultiStartRegistration.h"
#include "OccludingContourDetector.h"
#include "RegistrationData.h"
#include "SfmReconstruction.h"
#include "TriangleMesh.h"

#include <nlohmann/json.hpp>

#include <iosfwd>
#include <random>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief Settings of P2, the paper's simulated-video experiment.
struct VideoEvaluationOptions
{
  /// The sequence: frames (default 30), seed, camera, path (see EndoscopeSimulationOptions).
  EndoscopeSimulationOptions simulation;
  /// "builtin" (StructureFromMotion) or "colmap" (the `colmap` program, imported).
  std::string sfm = "builtin";
  /// The COLMAP executable and a folder for its work (default: a folder
  /// beside the result file, see runVideoEvaluation).
  std::string colmapExecutable = "colmap";
  std::string workFolder;
  /// Perturbation of the start: a rotation about the centroid of the points
  /// and a translation, magnitudes uniform in these ranges (defaults 2-3 mm
  /// and 2-3 degrees, P1's misalignment), on top of the true pose; the scale
  /// starts from the tracker (V14).
  double perturbMinMm = 2.0;
  double perturbMaxMm = 3.0;
  double perturbMinDeg = 2.0;
  double perturbMaxDeg = 3.0;
  /// Scale bounds: the initial scale divided and multiplied by this (default 1.25).
  double scaleBoundFactor = 1.25;
  /// The contour detector (its spacing thins the points the registration uses).
  OccludingContourDetector::Options contours;
  /// Contour noise model: Σ2d (px², isotropic) and κ (defaults 1 and 200,
  /// the paper's values for video contours).
  double contourVariancePx2 = 1.0;
  double kappa = 200.0;
  /// Added to every SfM point covariance (mm, std): the mesh's own error and
  /// what triangulation geometry does not capture (default 0.1).
  double pointNoiseFloorMm = 0.1;
  /// V11 for this problem: stop when the cost has not fallen by 0.001 %
  /// (default 1e-5) for 10 iterations, at most 300 iterations. With about
  /// 1500 SfM points and thousands of contour points accurate to a fraction
  /// of a pixel, the cost falls slowly near the optimum, and the registration
  /// options' default stall rule (0.1 % in 5 iterations) ends the run before
  /// the estimate settles; the change thresholds then decide convergence.
  double stallRelativeDecrease = 1e-5;
  int stallIterations = 10;
  int maxIterations = 300;
  int threads = 0;
  /// The start: "perturbed" (the truth moved by the ranges above) or
  /// "canonical" (the multi-start from canonical poses, V13 b).
  std::string init = "perturbed";
  /// With "canonical": the poses, the multi-start, and the roll spread of the
  /// simulated scope, held upright within this many degrees (default 10).
  CanonicalPoseOptions canonical;
  MultiStartOptions multiStart;
  double uprightRollDeg = 10.0;
};

/// @brief A simulated sequence turned into registration data, with its truth.
struct VideoCase
{
  SimulatedVideo video;
  nlohmann::json contourScores; ///< precision, recall, median normal error
  SfmReconstruction sfm;
  SimilarityTransform truth; ///< true SfM-to-CT similarity
  double initialScale = 1.0; ///< from the simulated tracker (V14)
  RegistrationData data;     ///< registered frames with contours, points with covariances
  std::vector<int> frameOf;  ///< data frame -> simulated frame
  Eigen::Vector3d centroidCT = Eigen::Vector3d::Zero(); ///< of the points, through the truth
  nlohmann::json floor; ///< camera errors of SfM through the true similarity
};

/**
 * @brief Simulates the sequence of `o` in `model`, detects and scores its
 * contours, runs SfM and the tracker scale, and builds the registration data.
 * @throws vimlop::Error when a stage fails (no path, too little SfM).
 */
VideoCase prepareVideoCase(
  const RegistrationModel& model, const VideoEvaluationOptions& o, std::ostream* progress);

/// @brief Mean/max camera position (mm) and angle (deg) errors and the scale error of `sfmToCT`.
nlohmann::json cameraErrors(const VideoCase& c, const SimilarityTransform& sfmToCT, double seconds);

/// @brief Per registered frame, the camera position error (mm) of `sfmToCT`.
std::vector<double> cameraPositionErrorsMm(const VideoCase& c, const SimilarityTransform& sfmToCT);

/**
 * @brief The truth at the tracker's scale, turned about the points' centroid
 * by an angle in [minDeg, maxDeg] and shifted by [minMm, maxMm], both in
 * random directions; drawn again until every camera is inside the airway.
 * @throws vimlop::Error when 500 draws leave a camera outside.
 */
SimilarityTransform perturbedStart(const VideoCase& c, const RegistrationModel& model,
  std::mt19937_64& rng, double minMm, double maxMm, double minDeg, double maxDeg);

/// @brief The registration options of P2 for `method` (noise, scale bounds, V11).
RegistrationOptions videoRegistrationOptions(
  double initialScale, const VideoEvaluationOptions& o, RegistrationMethod method);

/// @brief One start per pose: the middle registered frame (its id in
/// `anchorFrame`) placed at the pose, at the tracker's scale.
std::vector<SimilarityTransform> canonicalStarts(const RegistrationData& data, double initialScale,
  const std::vector<CameraPose>& posesCT, int* anchorFrame = nullptr);

/**
 * @brief The SfM-to-CT similarity that best carries the registered SfM
 * cameras onto `camerasCT` (one per SfM frame): the chordal mean rotation,
 * then least-squares scale and translation of the centres.
 */
SimilarityTransform similarityFromCameras(
  const SfmReconstruction& sfm, const std::vector<CameraPose>& camerasCT);

/**
 * @brief Runs P2 on `mesh`: simulates the sequence, detects contours (scored
 * against the true occluding contours), runs SfM, scales it from the
 * simulated tracker, perturbs the true SfM-to-CT transform, registers with
 * V-IMLOP and with IMLP, and returns the JSON report (see the user guide).
 * Progress goes to `progress` when given.
 * @throws vimlop::Error when any stage fails on its input.
 */
nlohmann::json runVideoEvaluation(
  const TriangleMesh& mesh, const VideoEvaluationOptions& options, std::ostream* progress);

} // namespace vimlop

#endif
