#ifndef vimlop_RegistrationVerdict_h
#define vimlop_RegistrationVerdict_h

#include <vimlop/Results/RegistrationRecord.h>

#include <string>

namespace vimlop
{

/// @brief Whether a result may be navigated with (V13).
enum class VerdictStatus
{
  Registered, ///< checked and not flagged
  Flagged,    ///< flagged as a failure: do not navigate with it
  Unchecked   ///< no failure check recorded (e.g. an evaluation's single registration)
};

/// @brief "registered", "flagged" or "unchecked".
const char* toString(VerdictStatus status);

/**
 * @brief The verdict on a registration, as the report's banner, its
 * report.json and the registered video's banner all state it: one place
 * turns a record's failure check (V13) into words, so that the three never
 * disagree.
 */
struct RegistrationVerdict
{
  VerdictStatus status = VerdictStatus::Unchecked;
  /// The result's contour error (V13's measure), px.
  double contourErrorPx = 0.0;
  /// The error above which a result is flagged, px (0 when unchecked).
  double thresholdPx = 0.0;
  /// The result's mean 3-D residual (V13's second measure), mm.
  double residualErrorMm = 0.0;
  /// The residual above which a result is flagged, mm (0 when unchecked, or
  /// a record from before the check had it: the headline then leaves it out).
  double thresholdResidualMm = 0.0;
  /// Why it is flagged (empty unless flagged).
  std::string reason;

  /// @brief The verdict of `record`: from its confidence, or Unchecked without one.
  static RegistrationVerdict of(const RegistrationRecord& record);

  /**
   * @brief One line for people, short enough for a video banner, e.g.
   * "REGISTERED: contour error 0.80 px, residual 0.21 mm (flagged above
   * 4.00 px or 0.80 mm)" or
   * "FLAGGED AS A FAILURE, do not navigate: the contour error 10.30 px is
   * above the threshold of 3.00 px".
   */
  std::string headline() const;
};

} // namespace vimlop

#endif
