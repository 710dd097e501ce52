#include <vimlop/Rendering/ReportCharts.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Rendering/ContourOverlay.h>
#include <vimlop/Rendering/WindowCapture.h>

#include <vtkAutoInit.h>
#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextActor.h>
#include <vtkContextScene.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <limits>

VTK_MODULE_INIT(vtkRenderingOpenGL2);
VTK_MODULE_INIT(vtkRenderingContextOpenGL2);
VTK_MODULE_INIT(vtkRenderingFreeType);

namespace vimlop
{

namespace
{

vtkSmartPointer<vtkImageData> renderChart(const ChartSpec& spec, int widthPx, int heightPx)
{
  vtkNew<vtkChartXY> chart;
  chart->SetTitle(spec.title);
  chart->GetTitleProperties()->SetFontSize(15);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(spec.xTitle);
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(spec.yTitle);
  chart->SetShowLegend(spec.series.size() > 1);
  if (spec.legendLeft)
  {
    chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::LEFT);
  }
  double xRange[2] = { std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity() };
  double yRange[2] = { xRange[0], xRange[1] };
  bool anyPoints = false;
  for (const ChartSpec::Series& series : spec.series)
  {
    if (series.x.size() != series.y.size())
    {
      throw Error("chart '" + spec.title + "': series '" + series.name +
        "' has x and y of different lengths");
    }
    vtkNew<vtkDoubleArray> x;
    x->SetName("x");
    vtkNew<vtkDoubleArray> y;
    y->SetName(series.name.c_str());
    for (size_t i = 0; i < series.x.size(); ++i)
    {
      x->InsertNextValue(series.x[i]);
      y->InsertNextValue(series.y[i]);
      xRange[0] = std::min(xRange[0], series.x[i]);
      xRange[1] = std::max(xRange[1], series.x[i]);
      yRange[0] = std::min(yRange[0], series.y[i]);
      yRange[1] = std::max(yRange[1], series.y[i]);
    }
    anyPoints = anyPoints || series.points;
    vtkNew<vtkTable> table;
    table->AddColumn(x);
    table->AddColumn(y);
    vtkPlot* plot = chart->AddPlot(series.points ? vtkChart::POINTS : vtkChart::LINE);
    plot->SetInputData(table, 0, 1);
    plot->SetLabel(series.name);
    plot->SetColor(series.colour[0], series.colour[1], series.colour[2], 255);
    plot->SetWidth(series.points ? 1.0f : 2.0f);
    if (auto* points = vtkPlotPoints::SafeDownCast(plot))
    {
      points->SetMarkerStyle(series.points ? vtkPlotPoints::CIRCLE : vtkPlotPoints::NONE);
      points->SetMarkerSize(series.points ? 7.0f : 0.0f);
    }
  }

  // Fixed ranges with a margin, so that markers at the ends stay whole and
  // lines do not run along the frame.
  if (xRange[0] <= xRange[1])
  {
    const double xPad = anyPoints ? 0.05 * std::max(xRange[1] - xRange[0], 1e-9) : 0.0;
    vtkAxis* bottom = chart->GetAxis(vtkAxis::BOTTOM);
    bottom->SetBehavior(vtkAxis::FIXED);
    bottom->SetRange(xRange[0] - xPad, xRange[1] + xPad);
    vtkAxis* left = chart->GetAxis(vtkAxis::LEFT);
    left->SetBehavior(vtkAxis::FIXED);
    if (spec.logY)
    {
      left->SetLogScale(true);
      left->SetUnscaledRange(yRange[0] / 1.2, yRange[1] * 1.2);
    }
    else
    {
      const double low = std::min(0.0, yRange[0]);
      left->SetRange(low, yRange[1] + 0.08 * std::max(yRange[1] - low, 1e-9));
    }
  }

  vtkNew<vtkContextActor> actor;
  actor->GetScene()->AddItem(chart);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1.0, 1.0, 1.0);
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  window->SetSize(widthPx, heightPx);
  return captureWindow(window);
}

} // namespace

vtkSmartPointer<vtkImageData> renderCharts(
  const std::vector<ChartSpec>& charts, int chartWidthPx, int heightPx)
{
  if (charts.empty())
  {
    throw Error("charts: nothing to draw");
  }
  std::vector<vtkSmartPointer<vtkImageData>> pictures;
  for (const ChartSpec& spec : charts)
  {
    pictures.push_back(renderChart(spec, chartWidthPx, heightPx));
  }
  return pictures.size() == 1 ? pictures.front() : placeSideBySide(pictures, 0);
}

} // namespace vimlop
