#include <vimlop/Results/RegistrationVerdict.h>

#include <gtest/gtest.h>

using namespace vimlop;

namespace
{

RegistrationRecord recordWithContourError(double contourErrorPx)
{
  RegistrationRecord record;
  record.result.contourErrorPx = contourErrorPx;
  return record;
}

} // namespace

TEST(RegistrationVerdict, AResultPassingTheCheckIsRegisteredWithItsErrorAndThreshold)
{
  RegistrationRecord record = recordWithContourError(0.8);
  record.confidence = RegistrationRecord::Confidence{ false, 3.0, "", "canonical", 150, 4 };
  const RegistrationVerdict verdict = RegistrationVerdict::of(record);
  EXPECT_EQ(verdict.status, VerdictStatus::Registered);
  EXPECT_STREQ(toString(verdict.status), "registered");
  EXPECT_EQ(verdict.headline(), "REGISTERED: contour error 0.80 px (flagged above 3.00 px)");
}

TEST(RegistrationVerdict, AResultCheckedOnItsResidualTooStatesBothMeasuresAndThresholds)
{
  RegistrationRecord record = recordWithContourError(0.8);
  record.result.residualErrorMm = 0.214;
  record.confidence = RegistrationRecord::Confidence{ false, 4.0, "", "canonical", 150, 4, 0.8 };
  const RegistrationVerdict verdict = RegistrationVerdict::of(record);
  EXPECT_EQ(verdict.status, VerdictStatus::Registered);
  EXPECT_DOUBLE_EQ(verdict.thresholdResidualMm, 0.8);
  EXPECT_EQ(verdict.headline(),
    "REGISTERED: contour error 0.80 px, residual 0.21 mm (flagged above 4.00 px or 0.80 mm)");
}

TEST(RegistrationVerdict, AFlaggedResultSaysDoNotNavigateAndWhy)
{
  RegistrationRecord record = recordWithContourError(10.3);
  record.confidence = RegistrationRecord::Confidence{ true, 3.0,
    "the contour error 10.30 px is above the threshold of 3.00 px", "canonical", 150, 4 };
  const RegistrationVerdict verdict = RegistrationVerdict::of(record);
  EXPECT_EQ(verdict.status, VerdictStatus::Flagged);
  EXPECT_STREQ(toString(verdict.status), "flagged");
  EXPECT_DOUBLE_EQ(verdict.thresholdPx, 3.0);
  EXPECT_EQ(verdict.headline(),
    "FLAGGED AS A FAILURE, do not navigate: the contour error 10.30 px is above the threshold "
    "of 3.00 px");

  // A flag without a reason (a hand-written result.json) still says what was measured.
  record.confidence->reason.clear();
  EXPECT_EQ(RegistrationVerdict::of(record).headline(),
    "FLAGGED AS A FAILURE, do not navigate: the contour error is 10.30 px (threshold 3.00 px)");
}

TEST(RegistrationVerdict, ARecordWithoutAFailureCheckIsNeverCalledRegistered)
{
  const RegistrationVerdict verdict = RegistrationVerdict::of(recordWithContourError(0.5));
  EXPECT_EQ(verdict.status, VerdictStatus::Unchecked);
  EXPECT_STREQ(toString(verdict.status), "unchecked");
  EXPECT_EQ(
    verdict.headline(), "NOT CHECKED: no failure check was recorded (contour error 0.50 px)");
}
