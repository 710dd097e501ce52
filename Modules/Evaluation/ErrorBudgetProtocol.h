#ifndef vimlop_ErrorBudgetProtocol_h
#define vimlop_ErrorBudgetProtocol_h

#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Evaluation/EvaluationProgress.h>
#include <vimlop/Evaluation/WorldPreset.h>
#include <vimlop/Pipeline/VideoRegistrationOptions.h>

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace vimlop
{

struct CTVolume;

/// @brief Settings of P5, the error budget (issue 14).
struct ErrorBudgetOptions
{
  /// Sequences per condition (default 20), seeds firstSeed, firstSeed + 1, ...
  int seeds = 20;
  std::uint64_t firstSeed = 1;
  /// Frames per sequence (default 10: P5 runs hundreds of sequences).
  int frames = 10;
  /// The sources varied alone (default: every one of errorSources()).
  std::vector<std::string> sources;
  /// Each source's levels, as fractions of its clinical value (default {1}:
  /// each source at its clinical value; {0.5, 1, 2} draws the curve).
  std::vector<double> levels{ 1.0 };
  /// Also the ideal world and every source together (the clinical preset).
  bool ideal = true;
  bool clinical = true;
  /// The methods compared (default V-IMLOP, IMLP, trimmed ICP).
  std::vector<RegistrationMethod> methods{ RegistrationMethod::VIMLOP, RegistrationMethod::IMLP,
    RegistrationMethod::TrimmedICP };
  /// The starts: the canonical multi-start (the main job's) and the truth
  /// perturbed by 2-3 mm and 2-3 degrees (P2's); both by default.
  bool canonicalStarts = true;
  bool perturbedStarts = true;
  double perturbMinMm = 2.0;
  double perturbMaxMm = 3.0;
  double perturbMinDeg = 2.0;
  double perturbMaxDeg = 3.0;
  /// A registration succeeds when its mean camera position error is at most
  /// this, mm (default 1, P3's).
  double successMm = 1.0;
  /// A registration is good when its mean camera position error is below
  /// this, mm (default 0.5): flagging a good one is a false flag (issue 15).
  double goodMm = 0.5;
  /// The main job's settings (the production defaults).
  VideoRegistrationOptions pipeline;
  /// Where each sequence's user files are written for the pipeline to read
  /// (frames, intrinsics.yaml, tracker.csv; the truth apart). Required.
  std::string workFolder;

  /// @throws vimlop::Error naming the first invalid setting.
  void validate() const;
};

/// @brief One method's figures in one condition, from one kind of start.
struct BudgetMethodFigures
{
  /// Per registration, the mean over its frames; then over the registrations.
  Summary cameraPositionMm;
  Summary cameraAngleDeg;
  /// Over every target of every registration.
  Summary treMm;
  double successRate = 0.0;
  /// ROC AUC of the final contour error as a detector of failures (null
  /// with no failure or no success).
  std::optional<double> failureAuc;
  /// Fraction of registrations the main job flagged as failures.
  double flaggedRate = 0.0;
  double meanRuntimeS = 0.0;
  /// Registrations the figures are over.
  int registrations = 0;
};

/// @brief One registration of P5: what the failure flag saw and how far off it was.
struct BudgetRegistration
{
  std::string condition;
  std::uint64_t seed = 0;
  std::string start; ///< "canonical" or "perturbed"
  std::string method;
  double cameraPositionMm = 0.0; ///< mean over the frames
  double cameraAngleDeg = 0.0;   ///< mean over the frames
  double contourErrorPx = 0.0;   ///< the result's mean contour error
  double matchedFraction = 0.0;  ///< of the video contour points, matched at the end
  /// What else a confidence could use, all known without the truth: the
  /// contour inliers among the matches, the 3-D inliers among the SfM
  /// points, the 3-D residual (mm), and the median and largest per-frame
  /// contour error (px) over the frames with a match.
  double contourInlierFraction = 0.0;
  double pointInlierFraction = 0.0;
  double residualErrorMm = 0.0;
  double frameContourErrorMedianPx = 0.0;
  double frameContourErrorMaxPx = 0.0;
  /// From the canonical multi-start: the least final contour error of a
  /// finalist that ended elsewhere (its cameras more than the success
  /// threshold from the winner's on average), px; empty when every finalist
  /// ended with the winner.
  std::optional<double> rivalContourErrorPx;
  bool flagged = false; ///< by the main job's failure flag
  double seconds = 0.0;
};

/**
 * @brief How a failure flag fares over registrations pooled across
 * conditions and starts (issue 15): failures (mean camera error above
 * `successMm`) it missed, good registrations (below `goodMm`) it flagged.
 */
struct FailureFlagFigures
{
  int registrations = 0;
  int failures = 0;
  int missed = 0; ///< failures not flagged
  int good = 0;
  int falseFlags = 0; ///< good registrations flagged
  /// ROC AUC of the contour error as a detector of failures (null without a
  /// failure or a success).
  std::optional<double> contourErrorAuc;
};

/// @brief The flag's figures over `registrations` (all of them, whatever their method).
FailureFlagFigures assessFailureFlag(
  const std::vector<BudgetRegistration>& registrations, double successMm, double goodMm);

/// @brief One condition of P5: the ideal world, a source at a level, or the clinical world.
struct BudgetCondition
{
  std::string name;
  /// The source varied (empty for "ideal" and "clinical"), its knob and value.
  std::string source;
  std::string knob;
  double value = 0.0;
  /// Keyed by method name: from the canonical multi-start and from perturbed starts.
  std::map<std::string, BudgetMethodFigures> canonical;
  std::map<std::string, BudgetMethodFigures> perturbed;
  /// The SfM floor: SfM's cameras through the true similarity.
  Summary floorPositionMm;
  Summary floorAngleDeg;
  /// The world: the truth's distance to the model (mean, mm).
  double truthToModelMeanMm = 0.0;
  /// Sequences that could not be registered at all (SfM failed, no path...), with why.
  std::vector<std::string> failedSequences;
  double runtimeS = 0.0;
};

/// @brief The result of P5.
struct ErrorBudgetReport
{
  int seeds = 0;
  int frames = 0;
  std::vector<BudgetCondition> conditions;
  /// Every registration, in the order they ran.
  std::vector<BudgetRegistration> registrations;
  /// The thresholds of success and of a good registration, mm.
  double successMm = 1.0;
  double goodMm = 0.5;
  double runtimeS = 0.0;

  /// @brief Per method, the failure flag over its registrations pooled across
  /// conditions and starts.
  std::map<std::string, FailureFlagFigures> failureFlag() const;

  /// @brief The report as `vimlop evaluate budget` writes it (layout in the user guide).
  nlohmann::json toJson() const;
  /// @brief One line per condition and method (canonical starts), then one
  /// per method for the pooled failure flag, as printed.
  std::vector<std::string> summaryLines() const;
};

/**
 * @brief Runs P5 on the CT `ct`: for every condition, the world
 * (makeSimulatedWorld, made once per condition) and `seeds` sequences in it
 * (simulateEndoscopeVideo), each written as a user has it and registered by
 * the main job (VideoRegistrationPipeline, from those files only) with every
 * method from every kind of start. Progress goes to `progress` ("P5: ...").
 * Needs an X display.
 * @throws vimlop::Error for invalid options or on cancellation; a sequence
 * that fails is counted in its condition's failedSequences, not thrown.
 */
ErrorBudgetReport runErrorBudgetProtocol(
  const CTVolume& ct, const ErrorBudgetOptions& options, const EvaluationProgress& progress);

/**
 * @brief Writes the report page of P5 into `folder`: index.html with the table
 * and, per source with levels, one chart of the camera position error
 * against the source's value (source-NAME.png). Needs an X display.
 * @throws vimlop::Error if the folder cannot be written.
 */
void writeErrorBudgetPage(const ErrorBudgetReport& report, const std::string& folder);

} // namespace vimlop

#endif
