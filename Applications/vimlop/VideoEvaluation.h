#ifndef vimlop_VideoEvaluation_h
#define vimlop_VideoEvaluation_h

#include "OccludingContourDetector.h"
#include "TriangleMesh.h"
#include "VideoSimulation.h"

#include <nlohmann/json.hpp>

#include <iosfwd>
#include <string>

namespace vimlop
{

/// @brief Settings of P2, the paper's simulated-video experiment.
struct VideoEvaluationOptions
{
  /// The sequence: frames (default 30), seed, camera, path (see VideoSimulationOptions).
  VideoSimulationOptions simulation;
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
};

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
