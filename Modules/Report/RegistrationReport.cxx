#include <vimlop/Report/RegistrationReport.h>

#include "CTSlices.h"
#include "InteractiveView.h"
#include "RegistrationCharts.h"

#include <vimlop/Core/ContourMatcher.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/KdTree2D.h>
#include <vimlop/Core/OccludingContours.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TaskPool.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Core/VisibleModelContours.h>
#include <vimlop/Imaging/CTVolume.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Rendering/ContourOverlay.h>
#include <vimlop/Rendering/PNGImageIO.h>
#include <vimlop/Rendering/RegistrationScene.h>
#include <vimlop/Rendering/vtkVIMLOPSilhouetteRenderer.h>
#include <vimlop/Results/InputIdentity.h>
#include <vimlop/Results/RecordJson.h>
#include <vimlop/Results/RegistrationRecordIO.h>
#include <vimlop/Results/RegistrationVerdict.h>

#include <vtkImageData.h>
#include <vtkNew.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace vimlop
{

namespace
{

using json = nlohmann::json;
namespace fs = std::filesystem;

struct ContourMeasure
{
  double meanPx = 0.0;
  int matched = 0;
};

/// V3-V5 at one camera: the mean distance of the matched video contour points.
ContourMeasure measureContours(const RegistrationModel& model, const VideoFrame& frame,
  const CameraPose& camera, const RegistrationOptions& options)
{
  OccludingContourOptions contourOptions;
  contourOptions.sampleSpacingPx = options.contourSampleSpacingPx;
  const std::vector<ModelContourPoint> seen =
    visibleModelContours(model, frame.intrinsics, camera, contourOptions);
  std::vector<Eigen::Vector2d> pixels;
  for (const ModelContourPoint& s : seen)
  {
    pixels.push_back(s.pixel);
  }
  const KdTree2D tree(std::move(pixels));
  ContourMeasure measure;
  double sum = 0.0;
  for (const ContourMatch& m : matchContours(frame.contour, seen, tree, options.contourMatch))
  {
    if (m.model >= 0)
    {
      sum += m.errorPx.norm();
      ++measure.matched;
    }
  }
  measure.meanPx = measure.matched ? sum / measure.matched : 0.0;
  return measure;
}

std::string number(double value, int decimals = 3)
{
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string jsonValueText(const json& value)
{
  if (value.is_number_float())
  {
    std::ostringstream s;
    s << value.get<double>();
    return s.str();
  }
  return value.is_string() ? value.get<std::string>() : value.dump();
}

/// Frames to draw: all, or `limit` spread evenly (first and last included).
std::vector<size_t> chooseFrames(size_t count, int limit)
{
  std::vector<size_t> chosen;
  if (limit <= 0 || static_cast<size_t>(limit) >= count)
  {
    for (size_t j = 0; j < count; ++j)
    {
      chosen.push_back(j);
    }
    return chosen;
  }
  for (int k = 0; k < limit; ++k)
  {
    const size_t j = limit == 1 ? 0 : (k * (count - 1)) / static_cast<size_t>(limit - 1);
    if (chosen.empty() || chosen.back() != j)
    {
      chosen.push_back(j);
    }
  }
  return chosen;
}

json perturbationSummary(const std::vector<PerturbationRun>& runs)
{
  std::map<long, std::vector<const PerturbationRun*>> byOffset;
  for (const PerturbationRun& run : runs)
  {
    byOffset[std::lround(run.offsetMm * 1000.0)].push_back(&run);
  }
  json offsets = json::array();
  for (const auto& [key, group] : byOffset)
  {
    std::vector<double> errors, contours;
    int successes = 0;
    for (const PerturbationRun* run : group)
    {
      errors.push_back(run->finalErrorMm);
      contours.push_back(run->contourErrorPx);
      successes += run->success;
    }
    offsets.push_back({ { "offset_mm", key / 1000.0 }, { "offset_deg", group.front()->offsetDeg },
      { "runs", group.size() }, { "success_rate", static_cast<double>(successes) / group.size() },
      { "final_error_mm_median", summarize(errors).median },
      { "contour_error_px_median", summarize(contours).median } });
  }
  return { { "runs", runs.size() }, { "offsets", offsets } };
}

/// The run behind a record: how it was started, how long it took, with what, on what.
json runJson(const RegistrationRecord& record)
{
  json run = { { "source", record.source }, { "command_line", record.commandLine },
    { "registration_runtime_s", record.result.runtimeSeconds },
    { "versions", recordjson::versionsJson(record) }, { "inputs", recordjson::inputsJson(record) },
    { "ct_identity", record.ctIdentity } };
  run["run_wall_s"] = record.runWallS > 0.0 ? json(record.runWallS) : json(nullptr);
  return run;
}

std::string runHtml(const json& run)
{
  std::ostringstream html;
  html << "<h2>Run</h2>\n<table>\n";
  const std::string command = run.at("command_line").get<std::string>();
  html << "<tr><td>command line</td><td style=\"text-align:left\">"
       << (command.empty() ? std::string("(not from a command line: ") +
                escapeHtml(run.at("source").get<std::string>()) + ")"
                           : "<pre>" + escapeHtml(command) + "</pre>")
       << "</td></tr>\n";
  html << "<tr><td>run time until the result (s)</td><td>"
       << (run.at("run_wall_s").is_null() ? std::string("not recorded")
                                          : number(run.at("run_wall_s").get<double>(), 1) +
                " (loading, SfM, contours, registration; the result folder's pictures, video and "
                "report follow)")
       << "</td></tr>\n";
  std::string versions;
  for (const auto& [name, version] : run.at("versions").items())
  {
    versions += (versions.empty() ? "" : ", ") + name + " " + version.get<std::string>();
  }
  html << "<tr><td>versions</td><td>" << escapeHtml(versions) << "</td></tr>\n";
  for (const auto& [key, value] : run.at("ct_identity").items())
  {
    html << "<tr><td>CT " << escapeHtml(key) << "</td><td>" << escapeHtml(value.get<std::string>())
         << "</td></tr>\n";
  }
  html << "</table>\n";
  if (!run.at("inputs").empty())
  {
    html << "<h3>Inputs</h3>\n<table>\n<tr><th>role</th><th>path</th><th>bytes</th>"
            "<th>SHA-256</th></tr>\n";
    for (const json& input : run.at("inputs"))
    {
      html << "<tr><td>" << escapeHtml(input.at("role").get<std::string>()) << "</td><td>"
           << escapeHtml(input.at("path").get<std::string>()) << "</td><td>"
           << input.at("bytes").get<std::uint64_t>() << "</td><td><code>"
           << escapeHtml(input.at("sha256").get<std::string>()) << "</code></td></tr>\n";
    }
    html << "</table>\n";
  }
  return html.str();
}

void writeText(const std::string& text, const fs::path& path)
{
  std::ofstream out(path);
  out << text;
  if (!out)
  {
    throwFileError(path.string(), "cannot write the file");
  }
}

} // namespace

RegistrationReport RegistrationReport::write(const RegistrationRecord* record,
  const std::string& resultFolder, const std::vector<PerturbationRun>& runs,
  const std::string& outFolder, const RegistrationReportOptions& options,
  const RegistrationModel* builtModel)
{
  if (!record && runs.empty())
  {
    throw Error("report: nothing to report (no registration result and no perturbation runs)");
  }
  const fs::path out(outFolder);
  std::error_code ec;
  fs::create_directories(out / "overlays", ec);
  if (!fs::is_directory(out / "overlays"))
  {
    throwFileError(outFolder, "cannot create the folder");
  }

  RegistrationReport report;
  json reportJson = { { "format", "vimlop-report" }, { "version", 1 } };
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">\n"
       << "<title>VIMLOP registration report</title>\n"
       << "<style>body{font-family:sans-serif;margin:2em;max-width:1200px}"
       << "table{border-collapse:collapse;margin:0.5em 0}"
       << "td,th{border:1px solid #ccc;padding:0.2em 0.6em;text-align:right}"
       << "th{background:#eee}td:first-child,th:first-child{text-align:left}"
       << "img{max-width:100%;border:1px solid #888}"
       << "pre{white-space:pre-wrap;word-break:break-all;background:#f4f4f4;padding:0.5em}"
       << ".verdict{padding:0.7em 1em;font-size:1.3em;font-weight:bold;color:#fff}"
       << ".registered{background:#1b7a2e}.flagged{background:#b3161b}"
       << ".unchecked{background:#7a6200}</style>\n"
       << "</head><body>\n<h1>VIMLOP registration report</h1>\n";

  if (record)
  {
    const RegistrationResult& result = record->result;
    // The verdict first, where nobody can miss it.
    const RegistrationVerdict verdict = RegistrationVerdict::of(*record);
    report.verdict = verdict;
    reportJson["verdict"] = { { "status", toString(verdict.status) },
      { "headline", verdict.headline() }, { "contour_error_px", verdict.contourErrorPx },
      { "threshold_px", verdict.thresholdPx }, { "residual_error_mm", verdict.residualErrorMm },
      { "threshold_residual_mm", verdict.thresholdResidualMm }, { "reason", verdict.reason } };
    html << "<div id=\"verdict\" class=\"verdict " << toString(verdict.status) << "\">"
         << escapeHtml(verdict.headline()) << "</div>\n";
    // The model's search structures once: the caller's when it has them.
    std::optional<RegistrationModel> ownModel;
    if (!builtModel)
    {
      ownModel.emplace(makeEmbreeRegistrationModel(record->model));
    }
    const RegistrationModel& model = builtModel ? *builtModel : *ownModel;
    vtkNew<vtkVIMLOPSilhouetteRenderer> silhouettes;
    silhouettes->SetMesh(record->model);

    // Per-frame overlays and contour errors, before and after.
    const size_t frameCount = std::min(record->data.frames.size(), result.frames.size());
    const std::vector<size_t> drawn = chooseFrames(frameCount, options.maxOverlayFrames);
    json framesJson = json::array();
    double sumBefore = 0.0;
    double sumAfter = 0.0;
    // The contour measures (V3-V5 with Embree, the report's costly numbers) of
    // every frame before and after, on the registration's threads: task 2j is
    // frame j before, 2j + 1 after, so the numbers do not depend on the thread count.
    std::vector<ContourMeasure> measures(2 * frameCount);
    TaskPool pool(record->options.threads);
    pool.run(static_cast<int>(measures.size()),
      [&](int task)
      {
        const size_t j = static_cast<size_t>(task / 2);
        const VideoFrame& frame = record->data.frames[j];
        const CameraPose camera = task % 2 == 0 ? record->initialSfmToCT.apply(frame.cameraToSfm)
                                                : result.frames[j].cameraToCT;
        measures[static_cast<size_t>(task)] =
          measureContours(model, frame, camera, record->options);
      });
    for (size_t j = 0; j < frameCount; ++j)
    {
      const VideoFrame& frame = record->data.frames[j];
      const CameraPose before = record->initialSfmToCT.apply(frame.cameraToSfm);
      const CameraPose after = result.frames[j].cameraToCT;
      Frame f;
      f.frameId = frame.frameId;
      const ContourMeasure& b = measures[2 * j];
      const ContourMeasure& a = measures[2 * j + 1];
      f.contourErrorBeforePx = b.meanPx;
      f.matchedBefore = b.matched;
      f.contourErrorAfterPx = a.meanPx;
      f.matchedAfter = a.matched;
      if (record->truth && j < record->truth->camerasCT.size())
      {
        f.cameraPositionErrorMm = cameraPositionError(after, record->truth->camerasCT[j]);
        f.cameraAngleErrorDeg = cameraAngleErrorDeg(after, record->truth->camerasCT[j]);
      }
      if (std::find(drawn.begin(), drawn.end(), j) != drawn.end())
      {
        vtkSmartPointer<vtkImageData> picture;
        if (j < record->frameImages.size() && !record->frameImages[j].empty())
        {
          picture = readPNG((fs::path(resultFolder) / record->frameImages[j]).string());
        }
        const int w = frame.intrinsics.widthPx;
        const int h = frame.intrinsics.heightPx;
        try
        {
          const auto left = composeContourOverlay(
            w, h, picture, silhouettes->RenderContours(frame.intrinsics, before), frame.contour);
          const auto right = composeContourOverlay(
            w, h, picture, silhouettes->RenderContours(frame.intrinsics, after), frame.contour);
          char name[64];
          std::snprintf(name, sizeof name, "overlays/frame-%04d.png", frame.frameId);
          writePNG(placeSideBySide({ left, right }, 4), (out / name).string());
          f.overlay = name;
          report.pictures.push_back(name);
        }
        catch (const Error& e)
        {
          throw Error("frame " + std::to_string(frame.frameId) + ": " + e.what());
        }
      }
      sumBefore += f.contourErrorBeforePx;
      sumAfter += f.contourErrorAfterPx;
      json fj = { { "id", f.frameId }, { "contour_error_before_px", f.contourErrorBeforePx },
        { "contour_error_after_px", f.contourErrorAfterPx }, { "matched_before", f.matchedBefore },
        { "matched_after", f.matchedAfter },
        { "registration_contour_error_px", result.frames[j].contourErrorPx },
        { "registration_contour_inliers", result.frames[j].inliers },
        { "overlay", f.overlay.empty() ? json(nullptr) : json(f.overlay) } };
      if (f.cameraPositionErrorMm)
      {
        fj["camera_position_error_mm"] = *f.cameraPositionErrorMm;
        fj["camera_angle_error_deg"] = *f.cameraAngleErrorDeg;
      }
      framesJson.push_back(fj);
      report.frames.push_back(f);
    }
    if (frameCount > 0)
    {
      report.contourErrorBeforePx = sumBefore / frameCount;
      report.contourErrorAfterPx = sumAfter / frameCount;
    }
    if (record->truth && !record->truth->targetsCT.empty())
    {
      report.treBeforeMm = targetRegistrationError(
        record->initialSfmToCT, record->truth->sfmToCT, record->truth->targetsCT);
      report.treAfterMm =
        targetRegistrationError(result.sfmToCT, record->truth->sfmToCT, record->truth->targetsCT);
    }

    // The 3-D scene and the iteration plots.
    std::vector<Eigen::Vector3d> registered;
    for (const Eigen::Vector3d& x : record->data.points)
    {
      registered.push_back(result.sfmToCT.apply(x));
    }
    std::vector<CameraPose> cameras;
    for (const FrameResult& fr : result.frames)
    {
      cameras.push_back(fr.cameraToCT);
    }
    const std::vector<CameraPose> trueCameras =
      record->truth ? record->truth->camerasCT : std::vector<CameraPose>();
    writePNG(renderRegistrationScene(record->model, registered, cameras, trueCameras,
               options.sceneWidthPx, options.sceneHeightPx),
      (out / "scene.png").string());
    report.pictures.push_back("scene.png");
    const std::string interactiveView =
      writeInteractiveView({ record->model, registered, cameras, trueCameras }, outFolder);
    // The scope in the CT: the middle frame's camera (the path as dots).
    std::string ctSlicesHtml;
    const std::string ctPath =
      options.ctPath.empty() ? recordedInputPath(*record, "ct") : options.ctPath;
    if (options.ctSlices && !ctPath.empty() && !cameras.empty())
    {
      const size_t shown = cameras.size() / 2;
      try
      {
        writeCTSlices(readCTVolume(ctPath), cameras, shown, (out / "ct-slices.png").string());
        report.pictures.push_back("ct-slices.png");
        const Eigen::Vector3d& c = cameras[shown].centre;
        ctSlicesHtml = "<h2>The scope in the CT</h2>\n<p>Frame " +
          std::to_string(result.frames[shown].frameId) + " (the middle of the sequence) at (" +
          number(c.x(), 1) + ", " + number(c.y(), 1) + ", " + number(c.z(), 1) +
          ") mm, LPS: its optical centre (ring) and view direction (arrow, 15 mm, projected), "
          "the other frames' centres as dots; " +
          formatText(
            "%.0f mm fields, bone window, from %s.", ctSliceFieldMm, escapeHtml(ctPath).c_str()) +
          "</p>\n<img src=\"ct-slices.png\" alt=\"axial, coronal and sagittal CT slices with the "
          "scope\">\n";
        reportJson["ct_slices"] = { { "ct", ctPath }, { "frame", result.frames[shown].frameId },
          { "centre_mm", { c.x(), c.y(), c.z() } } };
      }
      catch (const Error& e)
      {
        if (!options.ctPath.empty())
        {
          throw;
        }
        ctSlicesHtml = "<h2>The scope in the CT</h2>\n<p>Not drawn: the recorded CT could not be "
                       "read (" +
          escapeHtml(e.what()) + ").</p>\n";
      }
    }
    if (frameCount > 0)
    {
      writePNG(frameCharts(
                 report.frames, verdict.thresholdPx, options.chartWidthPx, options.chartHeightPx),
        (out / "frames.png").string());
      report.pictures.push_back("frames.png");
    }
    if (!result.history.empty())
    {
      writePNG(iterationCharts(*record, options.chartWidthPx, options.chartHeightPx),
        (out / "iterations.png").string());
      report.pictures.push_back("iterations.png");
    }

    const Eigen::Vector3d& t = result.sfmToCT.translation;
    json summary = { { "source", record->source }, { "method", toString(record->options.method) },
      { "termination", toString(result.termination) }, { "iterations", result.iterations },
      { "runtime_s", result.runtimeSeconds },
      { "transform", recordjson::transformJson(result.sfmToCT) },
      { "initial_transform", recordjson::transformJson(record->initialSfmToCT) },
      { "residual_error_mm", result.residualErrorMm },
      { "registration_contour_error_px", result.contourErrorPx },
      { "contour_error_before_px", report.contourErrorBeforePx },
      { "contour_error_after_px", report.contourErrorAfterPx },
      { "points", record->data.points.size() }, { "frames", frameCount } };
    if (report.treAfterMm)
    {
      summary["tre_before_mm"] = *report.treBeforeMm;
      summary["tre_after_mm"] = *report.treAfterMm;
    }
    reportJson["registration"] = summary;
    reportJson["frames"] = framesJson;
    reportJson["parameters"] = recordjson::optionsJson(record->options);

    html << "<p>" << escapeHtml(record->source) << "</p>\n<h2>Result</h2>\n<table>\n"
         << "<tr><td>method</td><td>" << toString(record->options.method) << "</td></tr>\n"
         << "<tr><td>termination</td><td>" << toString(result.termination) << " after "
         << result.iterations
         << " iterations (the winning start: " << number(result.runtimeSeconds, 2)
         << " s)</td></tr>\n"
         << "<tr><td>scale s</td><td>" << number(result.sfmToCT.scale, 5) << "</td></tr>\n"
         << "<tr><td>rotation angle (deg)</td><td>"
         << number(Eigen::AngleAxisd(result.sfmToCT.rotation).angle() * 180.0 / M_PI, 3)
         << "</td></tr>\n"
         << "<tr><td>translation t (mm)</td><td>(" << number(t.x(), 3) << ", " << number(t.y(), 3)
         << ", " << number(t.z(), 3) << ")</td></tr>\n"
         << "<tr><td>residual error (mm)</td><td>" << number(result.residualErrorMm)
         << "</td></tr>\n"
         << "<tr><td>contour error before / after (px)</td><td>"
         << number(report.contourErrorBeforePx, 2) << " / " << number(report.contourErrorAfterPx, 2)
         << "</td></tr>\n";
    if (report.treAfterMm)
    {
      html << "<tr><td>TRE before / after (mm)</td><td>" << number(*report.treBeforeMm) << " / "
           << number(*report.treAfterMm) << "</td></tr>\n";
    }
    html << "<tr><td>points (inliers)</td><td>" << record->data.points.size() << " ("
         << std::count(result.pointInliers.begin(), result.pointInliers.end(), 1)
         << ")</td></tr>\n</table>\n";
    html << "<h2>Frames</h2>\n<p>Model contours in green, video contours in white; before "
            "registration on the left, after on the right.</p>\n<table>\n<tr><th>frame</th>"
            "<th>contour error before (px)</th><th>after (px)</th><th>matched</th>";
    if (record->truth)
    {
      html << "<th>camera error (mm)</th><th>(deg)</th>";
    }
    html << "</tr>\n";
    for (const Frame& f : report.frames)
    {
      html << "<tr><td>" << f.frameId << "</td><td>" << number(f.contourErrorBeforePx, 2)
           << "</td><td>" << number(f.contourErrorAfterPx, 2) << "</td><td>" << f.matchedAfter
           << "</td>";
      if (f.cameraPositionErrorMm)
      {
        html << "<td>" << number(*f.cameraPositionErrorMm) << "</td><td>"
             << number(*f.cameraAngleErrorDeg) << "</td>";
      }
      html << "</tr>\n";
    }
    html << "</table>\n";
    if (frameCount > 0)
    {
      html << "<img src=\"frames.png\" alt=\"errors per frame\">\n";
    }
    for (const Frame& f : report.frames)
    {
      if (!f.overlay.empty())
      {
        html << "<h3>Frame " << f.frameId << "</h3>\n<img src=\"" << f.overlay << "\" alt=\"frame "
             << f.frameId << " before and after\">\n";
      }
    }
    html << "<h2>3-D scene</h2>\n<p>Airway cut open; registered SfM points in red, registered "
            "camera path in yellow"
         << (record->truth ? ", true cameras in cyan" : "") << ".</p>\n"
         << "<img src=\"scene.png\" alt=\"3-D scene\">\n<h3>Interactive view</h3>\n"
         << interactiveView << ctSlicesHtml;
    if (!result.history.empty())
    {
      html << "<h2>Iterations</h2>\n<img src=\"iterations.png\" alt=\"cost and errors per "
              "iteration\">\n";
    }
  }

  if (!runs.empty())
  {
    writePNG(perturbationCharts(runs, options.chartWidthPx, options.chartHeightPx),
      (out / "perturbation.png").string());
    report.pictures.push_back("perturbation.png");
    const json summary = perturbationSummary(runs);
    reportJson["perturbation"] = summary;
    html << "<h2>Perturbation study</h2>\n<img src=\"perturbation.png\" alt=\"final and "
            "contour error against initial offset\">\n<table>\n<tr><th>offset (mm)</th>"
            "<th>offset (deg)</th><th>runs</th><th>success rate</th><th>final error median "
            "(mm)</th><th>contour error median (px)</th></tr>\n";
    for (const json& o : summary.at("offsets"))
    {
      html << "<tr><td>" << number(o.at("offset_mm").get<double>(), 2) << "</td><td>"
           << number(o.at("offset_deg").get<double>(), 2) << "</td><td>" << o.at("runs")
           << "</td><td>" << number(100.0 * o.at("success_rate").get<double>(), 0) << " %</td><td>"
           << number(o.at("final_error_mm_median").get<double>()) << "</td><td>"
           << number(o.at("contour_error_px_median").get<double>(), 2) << "</td></tr>\n";
    }
    html << "</table>\n";
  }

  if (record)
  {
    reportJson["run"] = runJson(*record);
    html << runHtml(reportJson.at("run"));
    html << "<h2>Parameters</h2>\n<table>\n";
    for (const auto& [key, value] : reportJson.at("parameters").items())
    {
      html << "<tr><td>" << escapeHtml(key) << "</td><td>" << escapeHtml(jsonValueText(value))
           << "</td></tr>\n";
    }
    html << "</table>\n";
  }
  html << "<p>Numbers: <a href=\"report.json\">report.json</a>.</p>\n</body></html>\n";
  reportJson["pictures"] = report.pictures;
  report.reportJson = reportJson.dump(2) + "\n";
  writeText(report.reportJson, out / "report.json");
  writeText(html.str(), out / "index.html");
  return report;
}

} // namespace vimlop
