#ifndef vimlop_SyntheticProtocol_h
#define vimlop_SyntheticProtocol_h

#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Evaluation/EvaluationProgress.h>
#include <vimlop/Evaluation/SyntheticDataSurface.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief Settings of P1, the paper's synthetic experiment (DESIGN section 6).
struct SyntheticProtocolOptions
{
  /// Number of trials (default 100).
  int trials = 100;
  /// Random seed; trial i draws its data from seed * 1000003 + i (default 1).
  std::uint64_t seed = 1;
  /// The data of a trial: cameras, points, noise, misalignment (see
  /// SyntheticOptions), with the paper's contour noise (Σ2d = 9 px², κ = 200;
  /// SyntheticOptions::paper()).
  SyntheticOptions synthetic = SyntheticOptions::paper();
  /// Any of "vimlop", "imlp", "trimmed-icp", "open3d-icp", "open3d-gicp", each
  /// once, and Open3D's two with "-prebuilt": their target's k-d tree built
  /// once outside the timed part, like VIMLOP's model (Open3DPeers::TargetTree).
  std::vector<std::string> methods = { "vimlop", "imlp", "trimmed-icp", "open3d-icp", "open3d-gicp",
    "open3d-icp-prebuilt", "open3d-gicp-prebuilt" };
  /// A trial succeeds when its TRE is below this, mm (default 1).
  double successThresholdMm = 1.0;
  /// Scale bounds of VIMLOP's methods (the data's true scale is 1; defaults 0.8 and 1.25).
  double minScale = 0.8;
  double maxScale = 1.25;
  /// The paper's P1 noise model and stopping rule, set here rather than taken
  /// from RegistrationOptions (whose defaults are the video ones), so that P1
  /// figures stay those of the paper's settings: contour position variance
  /// Σ2d = this × I (default 9 px²), orientation concentration κ (default
  /// 200), stop when the cost has not fallen by this fraction (default 1e-3)
  /// for `stallIterations` (default 5) iterations, at most `maxIterations`
  /// (default 100).
  double contourVariancePx2 = 9.0;
  double kappa = 200.0;
  double stallRelativeDecrease = 1e-3;
  int stallIterations = 5;
  int maxIterations = 100;
  /// Threads per registration, 0 for all cores (default 0; results do not depend on it).
  int threads = 0;
  /// Model error (issue 14, item 4): the surface the points and contours
  /// are drawn from, in the model's frame, while the registration still has
  /// the model (makeSyntheticTrial(model, dataSurface, ...)). Default empty:
  /// the model itself, the paper's P1. See SyntheticDataSurface.h.
  TriangleMesh dataSurface;
  /// How `dataSurface` was made, for the record in the JSON (default: the model).
  SyntheticDataSurfaceOptions dataSurfaceMaking;
  /// Misspecified noise: the noise model the registration is given is this
  /// factor times the true one: the point covariances and the contour
  /// position variance Σ2d times it, κ divided by it (default 1: the true
  /// noise, as the paper). Finite and > 0. (A wrong start scale is
  /// `synthetic.startScaleError`.)
  double assumedNoiseScale = 1.0;
  /// RegistrationOptions::robustContourInflation for V-IMLOP (default off, as there).
  bool robustContourInflation = false;
  /// When not empty: trial 0 and its registration by the first of V-IMLOP,
  /// IMLP, trimmed ICP among `methods` are written to this result folder
  /// (see TrialSaving.h; needs an X display). Default empty.
  std::string saveTrialFolder;
};

/// @brief One method's figures over the trials of P1.
struct SyntheticProtocolMethodReport
{
  std::string method;
  /// Target registration error over the trials, mm.
  double treMeanMm = 0.0;
  double treMedianMm = 0.0;
  double treP95Mm = 0.0;
  /// Fraction of trials with a TRE below the success threshold.
  double successRate = 0.0;
  /// Median over trials and cameras of the camera position (mm) and angle (degrees) errors.
  double cameraPositionMedianMm = 0.0;
  double cameraAngleMedianDeg = 0.0;
  /// Median over trials of the 3-D residual: the mean distance of the
  /// registered points to the model's surface, mm (grows when the data are
  /// drawn from another surface than the model).
  double residualMedianMm = 0.0;
  /// Registration runtime per trial, s.
  double runtimeMedianS = 0.0;
  double runtimeP95S = 0.0;
};

/// @brief The result of P1.
struct SyntheticProtocolReport
{
  int trials = 0;
  std::uint64_t seed = 0;
  int meshTriangles = 0;
  double successThresholdMm = 0.0;
  /// The model error of the run: how the data surface was made (and its
  /// triangles; 0 for the model), the assumed noise scale, the start's scale error.
  SyntheticDataSurfaceOptions dataSurface;
  int dataSurfaceTriangles = 0;
  double assumedNoiseScale = 1.0;
  bool robustContourInflation = false;
  double startScaleError = 0.0;
  /// In the order of the options' methods.
  std::vector<SyntheticProtocolMethodReport> methods;

  /// @brief The report as written by `vimlop evaluate synthetic` (layout in the user guide).
  nlohmann::json toJson() const;
  /// @brief One line per method ("P1 vimlop TRE median ..."), as `vimlop evaluate synthetic`
  /// prints.
  std::vector<std::string> summaryLines() const;
};

/// @brief Every method name P1 knows, comma-separated (for messages).
const char* syntheticProtocolMethodNames();

/**
 * @throws vimlop::Error naming the first unknown or repeated method, or one
 * that needs Open3D when this build lacks it.
 */
void checkSyntheticProtocolMethods(const std::vector<std::string>& methods);

/**
 * @brief Checks the options that need no mesh: trials, assumed noise scale,
 * start scale error (1 + it within the scale bounds), the data surface's settings.
 * @throws vimlop::Error naming the first problem.
 */
void validateSyntheticProtocolOptions(const SyntheticProtocolOptions& options);

/**
 * @brief Runs P1: `trials` synthetic trials on `mesh`, every method on every
 * trial. Counts the trials to `progress` as "P1: trial".
 * @throws vimlop::Error for invalid options, an unusable mesh, or cancellation.
 */
SyntheticProtocolReport runSyntheticProtocol(const TriangleMesh& mesh,
  const SyntheticProtocolOptions& options, const EvaluationProgress& progress);

} // namespace vimlop

#endif
