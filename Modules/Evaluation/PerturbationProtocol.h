#ifndef vimlop_PerturbationProtocol_h
#define vimlop_PerturbationProtocol_h

#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Evaluation/EvaluationProgress.h>
#include <vimlop/Evaluation/VideoProtocol.h>
#include <vimlop/Results/PerturbationRuns.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace vimlop
{

/// @brief Settings of P3, robustness to the initial pose (DESIGN section 6).
struct PerturbationProtocolOptions
{
  /// The simulated sequence and the registration settings (those of P2;
  /// its threads run the registrations in parallel, one thread each).
  VideoProtocolOptions video;
  /// Offsets of the start: each is both a translation in mm and a rotation
  /// in degrees, in random directions (default 0, 2, 4, 6, 8, 10; each in [0, 90]).
  std::vector<double> offsets{ 0.0, 2.0, 4.0, 6.0, 8.0, 10.0 };
  /// Registrations per offset (default 10).
  int trialsPerOffset = 10;
  /// A run succeeds when its mean camera position error is at most this, mm (default 1).
  double successMm = 1.0;
  /// @throws vimlop::Error naming the first invalid setting.
  void validate() const;
};

/// @brief The runs of P3 at one offset.
struct PerturbationOffsetReport
{
  double offsetMm = 0.0;
  double offsetDeg = 0.0;
  int trials = 0;
  double successRate = 0.0;
  double cameraPositionMedianMm = 0.0;
  double contourErrorMedianPx = 0.0;
};

/// @brief The result of P3.
struct PerturbationProtocolReport
{
  std::uint64_t seed = 0;
  double successMm = 0.0;
  std::size_t sfmPoints = 0;
  std::vector<PerturbationOffsetReport> offsets;
  int runsTotal = 0;
  std::size_t failures = 0;
  /// How well contour error separates the failures from the successes (ROC
  /// area; a run matching fewer than half its video contour points counts as
  /// an infinite error), and the contour error that separates them best
  /// (Youden's J); none when all runs succeed or all fail.
  std::optional<double> auc;
  std::optional<double> failureThresholdPx;
  /// Every run, for the report's Fig. 3 (writePerturbationRuns).
  std::vector<PerturbationRun> runs;

  /// @brief p3.json as written by `vimlop evaluate perturbation` (without the runs).
  nlohmann::json toJson() const;
  /// @brief One line per offset, then the ROC line ("P3 ..."), as `vimlop
  /// evaluate perturbation` prints.
  std::vector<std::string> summaryLines() const;
};

/**
 * @brief Runs P3: one simulated sequence (as P2), then V-IMLOP from starts
 * perturbed by each offset, `trialsPerOffset` times (in parallel, each run
 * on one thread; the result does not depend on the thread count). Notes go
 * to `progress` ("P2: ..." for the sequence, "P3: run ..." per run).
 * @throws vimlop::Error for invalid options, when the sequence cannot be
 * prepared, or on cancellation.
 */
PerturbationProtocolReport runPerturbationProtocol(const TriangleMesh& mesh,
  const PerturbationProtocolOptions& options, const EvaluationProgress& progress);

} // namespace vimlop

#endif
