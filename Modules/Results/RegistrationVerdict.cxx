#include <vimlop/Results/RegistrationVerdict.h>

#include <vimlop/Core/TextFormat.h>

namespace vimlop
{

const char* toString(VerdictStatus status)
{
  switch (status)
  {
    case VerdictStatus::Registered:
      return "registered";
    case VerdictStatus::Flagged:
      return "flagged";
    case VerdictStatus::Unchecked:
      break;
  }
  return "unchecked";
}

RegistrationVerdict RegistrationVerdict::of(const RegistrationRecord& record)
{
  RegistrationVerdict verdict;
  verdict.contourErrorPx = record.result.contourErrorPx;
  if (!record.confidence)
  {
    return verdict;
  }
  verdict.thresholdPx = record.confidence->failureThresholdPx;
  verdict.residualErrorMm = record.result.residualErrorMm;
  verdict.thresholdResidualMm = record.confidence->failureResidualMm;
  if (record.confidence->failure)
  {
    verdict.status = VerdictStatus::Flagged;
    // A flagged record without a reason (written by hand, or by an older
    // version) still says why the check exists.
    verdict.reason = record.confidence->reason.empty()
      ? formatText("the contour error is %.2f px (threshold %.2f px)", verdict.contourErrorPx,
          verdict.thresholdPx)
      : record.confidence->reason;
  }
  else
  {
    verdict.status = VerdictStatus::Registered;
  }
  return verdict;
}

std::string RegistrationVerdict::headline() const
{
  switch (this->status)
  {
    case VerdictStatus::Registered:
      if (this->thresholdResidualMm > 0.0)
      {
        return formatText(
          "REGISTERED: contour error %.2f px, residual %.2f mm (flagged above %.2f px or %.2f mm)",
          this->contourErrorPx, this->residualErrorMm, this->thresholdPx,
          this->thresholdResidualMm);
      }
      return formatText("REGISTERED: contour error %.2f px (flagged above %.2f px)",
        this->contourErrorPx, this->thresholdPx);
    case VerdictStatus::Flagged:
      return "FLAGGED AS A FAILURE, do not navigate: " + this->reason;
    case VerdictStatus::Unchecked:
      break;
  }
  return formatText(
    "NOT CHECKED: no failure check was recorded (contour error %.2f px)", this->contourErrorPx);
}

} // namespace vimlop
