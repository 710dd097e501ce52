#include <vimlop/Evaluation/ErrorBudgetProtocol.h>

#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Rendering/PNGImageIO.h>
#include <vimlop/Rendering/ReportCharts.h>

#include <vtkImageData.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace vimlop
{

namespace fs = std::filesystem;

void writeErrorBudgetPage(const ErrorBudgetReport& report, const std::string& folder)
{
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec)
  {
    throwFileError(folder, "cannot create the folder (" + ec.message() + ")");
  }
  const BudgetCondition* ideal = nullptr;
  for (const BudgetCondition& c : report.conditions)
  {
    ideal = c.name == "ideal" ? &c : ideal;
  }
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>VIMLOP P5: the error "
          "budget</title>\n<style>body{font-family:sans-serif;margin:2em}table{border-collapse:"
          "collapse}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}</style>"
          "</head><body>\n<h1>P5: the error budget</h1>\n";
  html << "<p>" << report.seeds << " sequences of " << report.frames
       << " frames per condition; median over the registrations of their mean camera error; "
          "from the canonical multi-start unless said. Runtime "
       << formatText("%.0f", report.runtimeS) << " s.</p>\n";
  html << "<table><tr><th>condition</th><th>method</th><th>camera mm (median)</th><th>p95</th>"
          "<th>angle deg</th><th>TRE mm (median)</th><th>success</th><th>failure AUC</th>"
          "<th>from perturbed: camera mm</th><th>SfM floor mm</th></tr>\n";
  for (const BudgetCondition& c : report.conditions)
  {
    for (const auto& [name, f] : c.canonical)
    {
      const auto p = c.perturbed.find(name);
      html << "<tr><td>" << c.name << "</td><td>" << name << "</td><td>"
           << formatText("%.3f", f.cameraPositionMm.median) << "</td><td>"
           << formatText("%.3f", f.cameraPositionMm.p95) << "</td><td>"
           << formatText("%.3f", f.cameraAngleDeg.median) << "</td><td>"
           << formatText("%.3f", f.treMm.median) << "</td><td>"
           << formatText("%.0f %%", 100.0 * f.successRate) << "</td><td>"
           << (f.failureAuc ? formatText("%.2f", *f.failureAuc) : std::string("-")) << "</td><td>"
           << (p != c.perturbed.end() ? formatText("%.3f", p->second.cameraPositionMm.median)
                                      : std::string("-"))
           << "</td><td>" << formatText("%.3f", c.floorPositionMm.median) << "</td></tr>\n";
    }
  }
  html << "</table>\n";

  // One chart per source: the camera error against its value, the ideal world at its off value.
  std::map<std::string, std::vector<const BudgetCondition*>> bySource;
  for (const BudgetCondition& c : report.conditions)
  {
    if (!c.source.empty())
    {
      bySource[c.source].push_back(&c);
    }
  }
  const std::array<std::array<unsigned char, 3>, 3> colours{ { { 31, 119, 180 }, { 255, 127, 14 },
    { 44, 160, 44 } } };
  for (const auto& [source, conditions] : bySource)
  {
    ChartSpec chart;
    chart.title = "P5: " + source;
    chart.xTitle = conditions.front()->knob;
    chart.yTitle = "camera position error, mm (median)";
    std::map<std::string, ChartSpec::Series> series;
    for (const BudgetCondition* c : conditions)
    {
      for (const auto& [name, f] : c->canonical)
      {
        series[name].x.push_back(c->value);
        series[name].y.push_back(f.cameraPositionMm.median);
      }
    }
    std::size_t i = 0;
    for (auto& [name, s] : series)
    {
      if (ideal && ideal->canonical.count(name))
      {
        s.x.insert(s.x.begin(), errorSource(source).offValue);
        s.y.insert(s.y.begin(), ideal->canonical.at(name).cameraPositionMm.median);
      }
      s.name = name;
      s.colour = colours[i++ % colours.size()];
      s.points = s.x.size() < 2;
      chart.series.push_back(s);
    }
    const std::string png = "source-" + source + ".png";
    writePNG(renderCharts({ chart }, 560, 360), (fs::path(folder) / png).string());
    html << "<h2>" << source << "</h2><img src=\"" << png << "\" alt=\"" << source << "\">\n";
  }
  html << "</body></html>\n";
  std::ofstream((fs::path(folder) / "index.html").string()) << html.str();
}

} // namespace vimlop
