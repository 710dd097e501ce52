#include <vimlop/Cohort/CohortReportPage.h>

#include <vimlop/Cohort/CohortTable.h>
#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TextFormat.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace vimlop
{

using nlohmann::json;

namespace
{

std::string cellText(const json& row, const std::string& column, const char* format)
{
  if (!row.contains(column))
  {
    return "";
  }
  const json& value = row.at(column);
  if (value.is_number())
  {
    return formatText(format, value.get<double>());
  }
  return escapeHtml(value.is_string() ? value.get<std::string>() : value.dump());
}

} // namespace

std::string histogramSvg(
  const std::vector<double>& values, const std::string& label, int widthPx, int heightPx)
{
  std::string svg = formatText("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" "
                               "height=\"%d\" role=\"img\" aria-label=\"%s\">\n",
    widthPx, heightPx, escapeHtml(label).c_str());
  if (values.empty())
  {
    return svg +
      formatText("<text x=\"10\" y=\"%d\">%s: no row has this figure</text>\n</svg>\n",
        heightPx / 2, escapeHtml(label).c_str());
  }
  const double lo = *std::min_element(values.begin(), values.end());
  const double hi = *std::max_element(values.begin(), values.end());
  // About the square root of the count, as bins; one when all are equal.
  const int bins = hi > lo
    ? std::clamp(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(values.size())))), 1, 30)
    : 1;
  std::vector<int> counts(static_cast<size_t>(bins), 0);
  for (double v : values)
  {
    const int b = hi > lo ? std::min(bins - 1, static_cast<int>((v - lo) / (hi - lo) * bins)) : 0;
    ++counts[static_cast<size_t>(b)];
  }
  const int most = *std::max_element(counts.begin(), counts.end());
  const double left = 40.0, right = widthPx - 10.0, top = 10.0, bottom = heightPx - 40.0;
  const double barWidth = (right - left) / bins;
  for (int b = 0; b < bins; ++b)
  {
    const double h = (bottom - top) * counts[static_cast<size_t>(b)] / most;
    svg += formatText("<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" "
                      "fill=\"#4a78b0\"><title>%d</title></rect>\n",
      left + b * barWidth + 1.0, bottom - h, std::max(1.0, barWidth - 2.0), h,
      counts[static_cast<size_t>(b)]);
  }
  const Summary s = summarize(values);
  const double medianX =
    hi > lo ? left + (s.median - lo) / (hi - lo) * (right - left) : (left + right) / 2.0;
  svg += formatText("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#c03030\" "
                    "stroke-dasharray=\"4 3\"/>\n",
    medianX, top, medianX, bottom);
  svg += formatText("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#333\"/>\n",
    left, bottom, right, bottom);
  svg += formatText(
    "<text x=\"%.1f\" y=\"%.1f\" font-size=\"11\">%.4g</text>\n", left, bottom + 14.0, lo);
  svg +=
    formatText("<text x=\"%.1f\" y=\"%.1f\" font-size=\"11\" text-anchor=\"end\">%.4g</text>\n",
      right, bottom + 14.0, hi);
  svg += formatText("<text x=\"4\" y=\"%.1f\" font-size=\"11\">%d</text>\n", top + 10.0, most);
  svg += formatText("<text x=\"%.1f\" y=\"%d\" font-size=\"12\" text-anchor=\"middle\">%s "
                    "(n %zu, median %.4g, p95 %.4g)</text>\n",
    (left + right) / 2.0, heightPx - 8, escapeHtml(label).c_str(), values.size(), s.median, s.p95);
  return svg + "</svg>\n";
}

void writeCohortReportPage(
  const CohortTable& table, const std::string& title, const std::string& folder)
{
  std::map<std::string, int> states;
  for (const json& row : table.rows)
  {
    ++states[row.value("state", "")];
  }
  std::string counts;
  for (const auto& [state, count] : states)
  {
    counts += (counts.empty() ? "" : ", ") + std::to_string(count) + " " + escapeHtml(state);
  }
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                     "<title>VIMLOP cohort: " +
    escapeHtml(title) +
    "</title>\n<style>body{font-family:sans-serif;margin:2em;max-width:72em}"
    "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:2px 6px;"
    "text-align:left}.failed{color:#a00}.figures svg{margin:0 1em 1em 0}</style>\n"
    "</head>\n<body>\n<h1>VIMLOP cohort: " +
    escapeHtml(title) + "</h1>\n";
  html += "<p>" + std::to_string(table.rows.size()) + " rows: " + counts +
    ". The table: <a href=\"../table.csv\">table.csv</a>, <a href=\"../table.json\">"
    "table.json</a>.</p>\n";
  html += "<h2>Distributions over the rows</h2>\n<div class=\"figures\">\n";
  html += histogramSvg(
    table.numbers("camera_position_error_mm_mean"), "mean camera error against the truth, mm");
  html += histogramSvg(table.numbers("contour_error_px"), "contour error, px");
  html += histogramSvg(table.numbers("wall_s"), "runtime of a row, s");
  html += "</div>\n";
  const auto failures = table.rowsIn({ "failed", "interrupted", "changed", "not run", "running" });
  html += "<h2>Rows without a result (" + std::to_string(failures.size()) + ")</h2>\n";
  if (failures.empty())
  {
    html += "<p>None: every row has its result.</p>\n";
  }
  else
  {
    html += "<table>\n<tr><th>id</th><th>command</th><th>state</th><th>error</th><th>log</th>"
            "</tr>\n";
    for (const json* row : failures)
    {
      const std::string id = row->value("id", "");
      html += "<tr class=\"failed\"><td>" + escapeHtml(id) + "</td><td>" +
        cellText(*row, "command", "%g") + "</td><td>" + cellText(*row, "state", "%g") +
        "</td><td>" + cellText(*row, "error", "%g") + "</td><td><a href=\"../logs/" +
        escapeHtml(id) + ".log\">log</a></td></tr>\n";
    }
    html += "</table>\n";
  }
  html += "<h2>Every row</h2>\n<table>\n<tr><th>id</th><th>command</th><th>state</th>"
          "<th>camera error, mm</th><th>contour error, px</th><th>runtime, s</th><th>host</th>"
          "</tr>\n";
  for (const json& row : table.rows)
  {
    html += "<tr><td>" + cellText(row, "id", "%g") + "</td><td>" + cellText(row, "command", "%g") +
      "</td><td>" + cellText(row, "state", "%g") + "</td><td>" +
      cellText(row, "camera_position_error_mm_mean", "%.3f") + "</td><td>" +
      cellText(row, "contour_error_px", "%.2f") + "</td><td>" + cellText(row, "wall_s", "%.1f") +
      "</td><td>" + cellText(row, "host", "%g") + "</td></tr>\n";
  }
  html += "</table>\n</body>\n</html>\n";
  writeFileAtomically(folder + "/index.html", html);
}

} // namespace vimlop
