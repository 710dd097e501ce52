#ifndef vimlop_ReportCharts_h
#define vimlop_ReportCharts_h

#include "VIMLOPRenderingModule.h"

#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

class vtkImageData;

namespace vimlop
{

/**
 * @brief One x-y chart of a report: a title, axis titles (with units) and
 * series drawn as lines or as points (vtkChartXY).
 */
struct ChartSpec
{
  /// A series: x and y of equal length, its legend name and colour.
  struct Series
  {
    std::string name;
    std::vector<double> x;
    std::vector<double> y;
    std::array<unsigned char, 3> colour = { 31, 119, 180 };
    /// Points (scatter) instead of a line.
    bool points = false;
  };

  std::string title;
  std::string xTitle;
  std::string yTitle;
  std::vector<Series> series;
  /// Logarithmic y axis (for costs spanning decades); values must be positive.
  bool logY = false;
  /// The legend in the top left corner instead of the top right (where the data leave room).
  bool legendLeft = false;
};

/**
 * @brief Renders `charts` offscreen side by side, each `chartWidthPx` x
 * `heightPx` pixels on white, with VTK's charts (vtkChartXY in a
 * vtkContextActor, text by FreeType). RGB unsigned char, row 0 at the
 * bottom. Needs an X display.
 * @throws vimlop::Error for no charts or a series whose x and y differ in length.
 */
VIMLOPRENDERING_EXPORT vtkSmartPointer<vtkImageData> renderCharts(
  const std::vector<ChartSpec>& charts, int chartWidthPx, int heightPx);

} // namespace vimlop

#endif
