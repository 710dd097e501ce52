#ifndef vimlop_RegistrationCharts_h
#define vimlop_RegistrationCharts_h

// Private to the Report module: the report's charts, drawn from a record.

#include <vimlop/Report/RegistrationReport.h>
#include <vimlop/Results/PerturbationRuns.h>
#include <vimlop/Results/RegistrationRecord.h>

#include <vtkSmartPointer.h>

#include <vector>

class vtkImageData;

namespace vimlop
{

/**
 * @brief The cost and the errors (residual, contour, and TRE and camera
 * position error when the record has a truth) per iteration of the winner.
 */
vtkSmartPointer<vtkImageData> iterationCharts(
  const RegistrationRecord& record, int chartWidthPx, int chartHeightPx);

/**
 * @brief Per frame of the result: the contour error before and after
 * registration beside the failure threshold (when `thresholdPx` > 0), and,
 * when the frames have errors against a truth, the camera's position and
 * angle errors.
 */
vtkSmartPointer<vtkImageData> frameCharts(const std::vector<RegistrationReport::Frame>& frames,
  double thresholdPx, int chartWidthPx, int chartHeightPx);

/**
 * @brief Final error and contour error against the initial offset of each
 * perturbation run, successes and failures apart.
 */
vtkSmartPointer<vtkImageData> perturbationCharts(
  const std::vector<PerturbationRun>& runs, int chartWidthPx, int chartHeightPx);

} // namespace vimlop

#endif
