#include "RegistrationCharts.h"

#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Rendering/ReportCharts.h>

#include <vtkImageData.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace vimlop
{

namespace
{

const std::array<unsigned char, 3> blue = { 31, 119, 180 };
const std::array<unsigned char, 3> orange = { 255, 127, 14 };
const std::array<unsigned char, 3> green = { 44, 160, 44 };
const std::array<unsigned char, 3> red = { 214, 39, 40 };
const std::array<unsigned char, 3> purple = { 148, 103, 189 };

std::vector<double> positive(std::vector<double> values, std::vector<double>& x)
{
  std::vector<double> keptX;
  std::vector<double> keptY;
  for (size_t i = 0; i < values.size(); ++i)
  {
    if (values[i] > 0.0 && std::isfinite(values[i]))
    {
      keptX.push_back(x[i]);
      keptY.push_back(values[i]);
    }
  }
  x = keptX;
  return keptY;
}

ChartSpec::Series series(const std::string& name, std::vector<double> x, std::vector<double> y,
  const std::array<unsigned char, 3>& colour, bool points = false)
{
  ChartSpec::Series s;
  s.name = name;
  s.x = std::move(x);
  s.y = std::move(y);
  s.colour = colour;
  s.points = points;
  return s;
}

} // namespace

vtkSmartPointer<vtkImageData> iterationCharts(
  const RegistrationRecord& record, int chartWidthPx, int chartHeightPx)
{
  const std::vector<IterationRecord>& history = record.result.history;
  std::vector<double> iteration;
  std::vector<double> cost;
  std::vector<double> residual;
  std::vector<double> contourIteration;
  std::vector<double> contour;
  std::vector<double> tre;
  std::vector<double> camera;
  for (const IterationRecord& r : history)
  {
    iteration.push_back(r.iteration);
    cost.push_back(r.cost);
    residual.push_back(r.residualErrorMm);
    if (r.withContours)
    {
      contourIteration.push_back(r.iteration);
      contour.push_back(r.contourErrorPx);
    }
    if (record.truth)
    {
      if (!record.truth->targetsCT.empty())
      {
        tre.push_back(
          targetRegistrationError(r.transform, record.truth->sfmToCT, record.truth->targetsCT));
      }
      double sum = 0.0;
      const size_t n = std::min(record.truth->camerasCT.size(), record.data.frames.size());
      for (size_t j = 0; j < n; ++j)
      {
        sum += cameraPositionError(
          r.transform.apply(record.data.frames[j].cameraToSfm), record.truth->camerasCT[j]);
      }
      if (n > 0)
      {
        camera.push_back(sum / n);
      }
    }
  }
  ChartSpec costChart;
  costChart.title = "Cost per iteration";
  costChart.xTitle = "iteration";
  costChart.yTitle = "cost (sum of C3d and C2d over inliers)";
  costChart.logY = true;
  std::vector<double> costX = iteration;
  std::vector<double> costY = positive(cost, costX);
  costChart.series.push_back(series("cost", costX, costY, blue));

  ChartSpec errorChart;
  errorChart.title = "Errors per iteration";
  errorChart.xTitle = "iteration";
  errorChart.yTitle = "error (mm; contour error in px)";
  errorChart.series.push_back(series("residual (mm)", iteration, residual, blue));
  if (!contour.empty())
  {
    errorChart.series.push_back(series("contour (px)", contourIteration, contour, orange));
  }
  if (!tre.empty())
  {
    errorChart.series.push_back(series("TRE (mm)", iteration, tre, green));
  }
  if (!camera.empty())
  {
    errorChart.series.push_back(series("camera position (mm)", iteration, camera, purple));
  }
  return renderCharts({ costChart, errorChart }, chartWidthPx, chartHeightPx);
}

vtkSmartPointer<vtkImageData> frameCharts(const std::vector<RegistrationReport::Frame>& frames,
  double thresholdPx, int chartWidthPx, int chartHeightPx)
{
  std::vector<double> id, before, after, truthId, position, angle;
  for (const RegistrationReport::Frame& f : frames)
  {
    id.push_back(f.frameId);
    before.push_back(f.contourErrorBeforePx);
    after.push_back(f.contourErrorAfterPx);
    if (f.cameraPositionErrorMm)
    {
      truthId.push_back(f.frameId);
      position.push_back(*f.cameraPositionErrorMm);
      angle.push_back(*f.cameraAngleErrorDeg);
    }
  }
  ChartSpec contour;
  contour.title = "Contour error per frame";
  contour.xTitle = "frame";
  contour.yTitle = "contour error (px)";
  contour.series.push_back(series("before", id, before, orange));
  contour.series.push_back(series("after", id, after, blue));
  if (thresholdPx > 0.0 && !id.empty())
  {
    // The threshold as a line across the frames: a frame above it is what flags a result.
    contour.series.push_back(series("failure threshold (on the mean)", { id.front(), id.back() },
      { thresholdPx, thresholdPx }, red));
  }
  std::vector<ChartSpec> charts = { contour };
  if (!truthId.empty())
  {
    ChartSpec camera;
    camera.title = "Camera error against the truth";
    camera.xTitle = "frame";
    camera.yTitle = "position error (mm); angle error (deg)";
    camera.series.push_back(series("position (mm)", truthId, position, purple));
    camera.series.push_back(series("angle (deg)", truthId, angle, green));
    charts.push_back(camera);
  }
  return renderCharts(charts, chartWidthPx, chartHeightPx);
}

vtkSmartPointer<vtkImageData> perturbationCharts(
  const std::vector<PerturbationRun>& runs, int chartWidthPx, int chartHeightPx)
{
  std::vector<double> okOffset, okError, okContour, badOffset, badError, badContour;
  for (const PerturbationRun& run : runs)
  {
    (run.success ? okOffset : badOffset).push_back(run.offsetMm);
    (run.success ? okError : badError).push_back(run.finalErrorMm);
    (run.success ? okContour : badContour).push_back(run.contourErrorPx);
  }
  ChartSpec error;
  error.title = "Final error against initial offset";
  error.xTitle = "initial offset (mm)";
  error.yTitle = "final error (mm)";
  ChartSpec contour;
  contour.title = "Contour error against initial offset";
  contour.xTitle = "initial offset (mm)";
  contour.yTitle = "contour error (px)";
  // Failures gather at large offsets and errors: the top left stays free.
  error.legendLeft = true;
  contour.legendLeft = true;
  if (!okOffset.empty())
  {
    error.series.push_back(series("success", okOffset, okError, blue, true));
    contour.series.push_back(series("success", okOffset, okContour, blue, true));
  }
  if (!badOffset.empty())
  {
    error.series.push_back(series("failure", badOffset, badError, red, true));
    contour.series.push_back(series("failure", badOffset, badContour, red, true));
  }
  return renderCharts({ error, contour }, chartWidthPx, chartHeightPx);
}

} // namespace vimlop
