#ifndef vimlop_VideoProtocol_h
#define vimlop_VideoProtocol_h

#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Evaluation/ContourScoring.h>
#include <vimlop/Evaluation/EndoscopeSimulation.h>
#include <vimlop/Evaluation/EvaluationProgress.h>
#include <vimlop/Pipeline/VideoRegistrationPipeline.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vimlop
{

struct SimulatedWorld;

/// @brief Settings of P2, the paper's simulated-video experiment (DESIGN section 6).
struct VideoProtocolOptions
{
  /// The sequence: frames (default 30), seed, camera, path (see EndoscopeSimulationOptions).
  EndoscopeSimulationOptions simulation;
  /// "builtin" (StructureFromMotion) or "colmap" (the `colmap` program, imported).
  std::string sfm = "builtin";
  /// The COLMAP executable (default "colmap") and a folder for its work
  /// (default empty: "p2-colmap" in the working folder).
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
  /// The registration: noise model, V11, scale bounds, point noise floor,
  /// contour detector, canonical poses, multi-start, threads (the production
  /// defaults, those of `vimlop register`).
  VideoRegistrationOptions pipeline;
  /// The start: "perturbed" (the truth moved by the ranges above) or
  /// "canonical" (the multi-start from canonical poses, V13 b). Default "perturbed".
  std::string init = "perturbed";
  /// With "canonical" and a free roll in `simulation`: the simulated scope is
  /// held upright within this many degrees (default 10), as canonical poses assume.
  double uprightRollDeg = 10.0;

  /// @throws vimlop::Error naming the first invalid setting.
  void validate() const;
};

/// @brief Camera errors of an SfM-to-CT estimate over the registered frames.
struct VideoCameraErrors
{
  double positionMeanMm = 0.0;
  double positionMaxMm = 0.0;
  double angleMeanDeg = 0.0;
  double angleMaxDeg = 0.0;
  /// |estimated scale / true scale - 1|.
  double scaleErrorRel = 0.0;
  /// Registration runtime, s (0 for the SfM floor).
  double runtimeS = 0.0;
};

/// @brief The multi-start's account of its winner (P2 from canonical starts).
struct VideoMultiStartFigures
{
  bool failureFlag = false;
  double contourErrorPx = 0.0;
  double matchedFraction = 0.0;
  double failureThresholdPx = 0.0;
  double failureResidualMm = 0.0;
  int winner = -1;
  int skippedCandidates = 0;
};

/// @brief One method's result in P2.
struct VideoProtocolMethodReport
{
  /// "vimlop" or "imlp".
  std::string method;
  VideoCameraErrors errors;
  /// With canonical starts only.
  std::optional<VideoMultiStartFigures> multiStart;
};

/// @brief The result of P2.
struct VideoProtocolReport
{
  int frames = 0;
  std::uint64_t seed = 0;
  std::string sfm;
  std::size_t sfmPoints = 0;
  ContourScores contours;
  /// What SfM alone allows: its cameras through the true similarity.
  VideoCameraErrors sfmFloor;
  std::string init;
  /// With canonical starts: canonical poses times scale factors.
  std::optional<std::size_t> candidates;
  /// V-IMLOP, then IMLP.
  std::vector<VideoProtocolMethodReport> methods;

  /// @brief The report as written by `vimlop evaluate video` (layout in the user guide).
  nlohmann::json toJson() const;
  /// @brief The contour and SfM line, then per method its camera errors (and
  /// multi-start) lines ("P2 ..."), as `vimlop evaluate video` prints.
  std::vector<std::string> summaryLines() const;
};

/**
 * @brief Runs P2 on `mesh`: simulates the sequence, detects contours (scored
 * against the true occluding contours), runs SfM, scales it from the
 * simulated tracker, starts from the perturbed truth or the canonical poses,
 * and registers with V-IMLOP and with IMLP. Notes on every stage go to
 * `progress` ("P2: ...", the SfM's "sfm: ..."), and the frames rendered
 * are counted ("simulate: frame"). Needs an X display.
 * @throws vimlop::Error when an option is invalid, a stage fails on its
 * input, or on cancellation.
 */
VideoProtocolReport runVideoProtocol(const TriangleMesh& mesh, const VideoProtocolOptions& options,
  const EvaluationProgress& progress);

/**
 * @brief P2 in `world`: the sequence rendered from its truth, registered to
 * its model (from its canonical poses when it has them). The mesh version is
 * this in the ideal world of that mesh.
 */
VideoProtocolReport runVideoProtocol(const SimulatedWorld& world,
  const VideoProtocolOptions& options, const EvaluationProgress& progress);

} // namespace vimlop

#endif
