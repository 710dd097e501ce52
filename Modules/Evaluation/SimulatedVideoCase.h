#ifndef vimlop_SimulatedVideoCase_h
#define vimlop_SimulatedVideoCase_h

#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Evaluation/ContourScoring.h>
#include <vimlop/Evaluation/EndoscopeSimulation.h>
#include <vimlop/Evaluation/EvaluationProgress.h>
#include <vimlop/Evaluation/SimulatedWorld.h>
#include <vimlop/Evaluation/VideoProtocol.h>
#include <vimlop/Video/SfmReconstruction.h>

#include <memory>
#include <random>
#include <vector>

namespace vimlop
{

class VideoRegistrationPipeline;

/// @brief A simulated sequence turned into registration data, with its truth (P2, P3).
struct SimulatedVideoCase
{
  SimulatedVideo video;
  ContourScores contourScores;
  SfmReconstruction sfm;
  SimilarityTransform truth; ///< true SfM-to-CT similarity
  double initialScale = 1.0; ///< from the simulated tracker (V14)
  RegistrationData data;     ///< registered frames with contours, points with covariances
  std::vector<int> frameOf;  ///< data frame -> simulated frame
  Eigen::Vector3d centroidCT = Eigen::Vector3d::Zero(); ///< of the points, through the truth
  VideoCameraErrors floor; ///< camera errors of SfM through the true similarity
  /// The main job, run through stage 6 (the data) on the sequence's user
  /// files; its model is the world's. Register with it (setStarts, run) or
  /// with `data` and pipeline->model() directly.
  std::shared_ptr<VideoRegistrationPipeline> pipeline;
};

/**
 * @brief Simulates the sequence of `o` in `world` (rendering its truth),
 * writes it as a user has it (writeSimulatedVideo, the truth removed) into
 * `o.workFolder`/sequence (a temporary folder, removed after, when the work
 * folder is empty), and runs the main job's stages 1-6 on those files
 * (VideoRegistrationPipeline with `o.pipeline`: the world's model, the
 * frames with the calibrated intrinsics, contours within the field stop,
 * SfM, the tracker's scale, the data). Then the evaluation's part: the
 * contours scored against the true ones, the true similarity and the SfM
 * floor. Notes go to `progress` as "P2: ...". `o` is valid
 * (VideoProtocolOptions::validate).
 * @throws vimlop::Error when a stage fails (no path, too little SfM), or on
 * cancellation.
 */
SimulatedVideoCase prepareSimulatedVideoCase(
  const SimulatedWorld& world, const VideoProtocolOptions& o, const EvaluationProgress& progress);

/**
 * @brief Sets the truth of a case whose video, SfM, data and frameOf are
 * set: the true SfM-to-CT similarity (SfM cameras against the true ones),
 * the points' centroid through it, and the SfM floor.
 */
void setCaseTruth(SimulatedVideoCase& c);

/// @brief Mean/max camera position (mm) and angle (deg) errors and the scale error of `sfmToCT`.
VideoCameraErrors cameraErrors(
  const SimulatedVideoCase& c, const SimilarityTransform& sfmToCT, double seconds);

/// @brief Per registered frame, the camera position error (mm) of `sfmToCT`.
std::vector<double> cameraPositionErrorsMm(
  const SimulatedVideoCase& c, const SimilarityTransform& sfmToCT);

/**
 * @brief The truth at the tracker's scale, turned about the points' centroid
 * by an angle in [minDeg, maxDeg] and shifted by [minMm, maxMm], both in
 * random directions; drawn again until every camera is inside the airway.
 * @throws vimlop::Error when 500 draws leave a camera outside.
 */
SimilarityTransform perturbedStart(const SimulatedVideoCase& c, const RegistrationModel& model,
  std::mt19937_64& rng, double minMm, double maxMm, double minDeg, double maxDeg);

} // namespace vimlop

#endif
