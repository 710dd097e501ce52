#ifndef vimlop_MultiStartRegistration_h
#define vimlop_MultiStartRegistration_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/Registration.h>

#include <functional>
#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief Settings of the multi-start registration (V13 b): one V-IMLOP run
 * per start and scale variation, the least contour error wins.
 */
struct MultiStartOptions
{
  /// The registration every candidate runs (method, noise, trimming, scale
  /// bounds, iterations). Its `threads` is ignored: candidates run in
  /// parallel, each on one thread.
  RegistrationOptions registration;
  /// Factors applied to each start's scale (default 0.9, 1, 1.1: the paper's
  /// "slightly vary the initial scale"). A factor that leaves the scale
  /// bounds is clamped into them.
  std::vector<double> scaleFactors{ 0.9, 1.0, 1.1 };
  /// Screening (default 10 iterations): every start first runs this many
  /// iterations at the scale factor closest to 1, on a subsample of the data
  /// (`screeningStride`), and only the `finalists`
  /// starts with the least contour error then run to convergence, at every
  /// scale factor. 0 runs every candidate to convergence. Half the
  /// iterations register points alone (V-IMLOP's first stage), the other
  /// half add the contours, so the contour error that ranks the starts has
  /// begun to fall where a start is good.
  int screeningIterations = 10;
  /// Screening registers every `screeningStride`-th frame and SfM point
  /// (default 3): the ranking needs the gist of the data, not all of it.
  int screeningStride = 3;
  /// Starts kept after screening (default 3).
  int finalists = 3;
  /// Threads over candidates, 0 for all cores. The result does not depend on it.
  int threads = 0;
  /// Mean contour error (px) above which the winner is flagged as a failure
  /// (default 4 px). With `failureResidualErrorMm`, chosen on P5's
  /// registrations of seeds 1-9 where the model is not the anatomy and
  /// checked on seeds 10-27 (Documentation/Algorithm.md): at 6 px alone,
  /// nearly half of the registrations 1-3 mm off passed.
  double failureContourErrorPx = 4.0;
  /// Mean 3-D residual (mm, SfM points to the surface) above which the
  /// winner is flagged as a failure (default 0.8 mm, chosen with
  /// `failureContourErrorPx`): a pose can fit the contours of a wrong
  /// stretch of airway while its points stand off the walls.
  double failureResidualErrorMm = 0.8;
  /// Least fraction of the video contour points matched to a model contour
  /// at the end (default 0.5). A pose that sees no model contour (a camera
  /// facing a wall, or outside) has no matches and a mean error of zero over
  /// them: it must neither win nor pass as a success. Correct poses match
  /// nearly every video contour point.
  double minMatchedFraction = 0.5;
  /// @throws vimlop::Error naming the first invalid field.
  void validate() const;
};

/// @brief How one candidate (a start and a scale factor) fared.
struct MultiStartCandidate
{
  int start = 0;            ///< index into the starts
  double scaleFactor = 1.0; ///< applied to the start's scale
  SimilarityTransform initialSfmToCT;
  /// Empty when the candidate ran; otherwise why not (e.g. a camera outside the airway).
  std::string skipped;
  double screeningContourErrorPx = 0.0; ///< after screening (when screening ran)
  bool finalist = false;                ///< ran to convergence
  double contourErrorPx = 0.0;          ///< at its end
  double matchedFraction = 0.0;         ///< of the video contour points, at its end
  double residualErrorMm = 0.0;         ///< at its end
  /// T at its end (the screening's end for a start that was not a finalist).
  SimilarityTransform finalSfmToCT;
  int iterations = 0; ///< screening and final runs together
  TerminationReason termination = TerminationReason::MaxIterations;
};

/// @brief The outcome of a multi-start registration.
struct MultiStartResult
{
  RegistrationResult best; ///< the winner's full result
  int bestCandidate = -1;  ///< index into `candidates`
  std::vector<MultiStartCandidate> candidates;
  /// True when the winner is flagged as a failure (see failureReason()).
  bool failure = false;
  double failureThresholdPx = 0.0; ///< the options' failureContourErrorPx
  double failureResidualMm = 0.0;  ///< the options' failureResidualErrorMm
  /// Why the winner is flagged, empty when it is not.
  std::string failureReason;

  /// @brief Sets the failure flag, its reason and threshold from `best` (V13).
  void flagFailure(const MultiStartOptions& options);
};

/// @brief Progress: candidates finished of the phase's total ("screening" or
/// "final"). Return false to cancel. Called from one thread at a time.
using MultiStartProgress = std::function<bool(const char* phase, int done, int total)>;

/**
 * @brief The start T (SfM to CT) that puts the camera of a frame, posed
 * `cameraToSfm` in the SfM reconstruction, at `cameraToCT`, with scale `scale`.
 */
SimilarityTransform startFromCameraPose(
  const CameraPose& cameraToCT, const CameraPose& cameraToSfm, double scale);

/// @brief Matched video contour points over all video contour points of a result (0 when none).
double matchedContourFraction(const RegistrationResult& result);

/**
 * @brief The failure flag of V13 for one result: too few video contour
 * points matched, or a mean contour error or 3-D residual above the options'
 * thresholds.
 */
bool isFlaggedAsFailure(const RegistrationResult& result, const MultiStartOptions& options);

/**
 * @brief Why isFlaggedAsFailure() flags a result, in words for the user (e.g.
 * "only 12 % of the video contour points matched a model contour (at least
 * 50 % needed)"); empty when it does not. Too few matches come first: the
 * mean error over them then says nothing.
 */
std::string failureReason(const RegistrationResult& result, const MultiStartOptions& options);

/**
 * @brief Registers from every start in `startsSfmToCT` (times each scale
 * factor) and keeps the solution with the least mean contour error among
 * those that match at least `minMatchedFraction` of the video contour points
 * (ties: the lower candidate index), flagging it as a failure above the
 * threshold or below that fraction.
 * Candidates whose cameras do not all start inside the airway are skipped
 * with the reason. Results do not depend on the number of threads.
 *
 * @throws vimlop::Error for invalid options or data, no starts, no candidate
 * that could run (the message gives the first reason), or cancellation.
 */
MultiStartResult registerMultiStart(const RegistrationModel& model, const RegistrationData& data,
  const std::vector<SimilarityTransform>& startsSfmToCT, const MultiStartOptions& options,
  const MultiStartProgress& progress = MultiStartProgress());

} // namespace vimlop

#endif
