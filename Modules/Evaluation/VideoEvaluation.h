#ifndef vimlop_VideoEvaluation_h
#define vimlop_VideoEvaluation_h

#include "CanonicalPoses.h"
#include "MultiStartRegistration.h"
#include "OccludingContourDetector.h"
#include "RegistrationData.h"
#include "RegistrationOptions.h"
#include "SfmReconstruction.h"

#include <vector>

namespace vimlop
{

/**
 * @brief The settings of registering video to the model that P2, P3 and
 * `vimlop register` share: the production defaults. (Modules/Pipeline's
 * VideoRegistrationPipeline::Options is to take this role.)
 */
struct VideoEvaluationOptions
{
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
  /// of a pixel, the cost falls slowly near the optimum, and a stall rule of
  /// 0.1 % in 5 iterations ends the run before the estimate settles; the
  /// change thresholds then decide convergence.
  double stallRelativeDecrease = 1e-5;
  int stallIterations = 10;
  int maxIterations = 300;
  /// Threads, 0 for all cores (default 0).
  int threads = 0;
  /// The canonical poses and the multi-start from them (V13 b).
  CanonicalPoseOptions canonical;
  MultiStartOptions multiStart;
};

/// @brief The registration options for `method` (noise, scale bounds, V11).
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

} // namespace vimlop

#endif
