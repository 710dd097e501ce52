#ifndef vimlop_CohortReportPage_h
#define vimlop_CohortReportPage_h

#include <string>
#include <vector>

namespace vimlop
{

struct CohortTable;

/**
 * @brief Writes a cohort's report page, `folder`/index.html: the rows'
 * states, the distributions of camera error, contour error and runtime over
 * the rows (histograms drawn as SVG in the page, so that no display is
 * needed: a cluster's merge job has none), the failures with their errors
 * and logs, and every row's state and main figures. `title` heads it (the
 * manifest's name).
 * @throws vimlop::Error when the page cannot be written.
 */
void writeCohortReportPage(
  const CohortTable& table, const std::string& title, const std::string& folder);

/**
 * @brief A histogram of `values` as an SVG picture `widthPx` x `heightPx`:
 * bars over equal bins between the least and the greatest value, the
 * median marked, `label` under the axis; a note instead when there is no value.
 */
std::string histogramSvg(const std::vector<double>& values, const std::string& label,
  int widthPx = 420, int heightPx = 220);

} // namespace vimlop

#endif
