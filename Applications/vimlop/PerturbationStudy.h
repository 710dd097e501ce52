#ifndef vimlop_PerturbationStudy_h
#define vimlop_PerturbationStudy_h

#include "PerturbationRuns.h"
#include "TriangleMesh.h"
#include "VideoEvaluation.h"

#include <nlohmann/json.hpp>

#include <iosfwd>
#include <vector>

namespace vimlop
{

/// @brief Settings of P3, robustness to the initial pose.
struct PerturbationStudyOptions
{
  /// The simulated sequence and the registration settings (those of P2).
  VideoEvaluationOptions video;
  /// Offsets of the start: each is both a translation in mm and a rotation
  /// in degrees, in random directions (default 0, 2, 4, 6, 8, 10).
  std::vector<double> offsets{ 0.0, 2.0, 4.0, 6.0, 8.0, 10.0 };
  int trialsPerOffset = 10;
  /// A run succeeds when its mean camera position error is at most this (default 1 mm).
  double successMm = 1.0;
  /// @throws vimlop::Error naming the first invalid setting.
  void validate() const;
};

/**
 * @brief Runs P3: one simulated sequence (as P2), then V-IMLOP from starts
 * perturbed by each offset, `trialsPerOffset` times (in parallel, each run
 * on one thread; the result does not depend on the thread count). Returns
 * the p3.json report and fills `runs` (for the report's Fig. 3).
 *
 * The report holds "protocol", "seed", "success_mm", per offset "offset_mm",
 * "offset_deg", "trials", "success_rate", "camera_position_mm_median",
 * "contour_error_px_median"; "auc" (how well contour error separates the
 * failures from the successes, ROC area, a run matching fewer than half its
 * video contour points counting as an infinite error; null when all runs
 * succeed or all fail) and "failure_threshold_px" (the contour error that
 * separates them best, Youden's J; null likewise).
 * @throws vimlop::Error for invalid options or when the sequence cannot be prepared.
 */
nlohmann::json runPerturbationStudy(const TriangleMesh& mesh, const PerturbationStudyOptions& o,
  std::vector<PerturbationRun>& runs, std::ostream* progress);

} // namespace vimlop

#endif
