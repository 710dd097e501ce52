#include <vimlop/Results/RegistrationRecordIO.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Registration/RegistrationInputConversion.h>
#include <vimlop/Registration/RegistrationOutputConversion.h>
#include <vimlop/Results/RecordJson.h>

#include "TableFile.h"

#include <nlohmann/json.hpp>

#include <cstdio>

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTable.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLTableReader.h>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

namespace vimlop
{

namespace
{

using json = nlohmann::json;
namespace fs = std::filesystem;
using namespace recordjson;

json timesJson(const StageTimes& t)
{
  return { { "match_3d", t.match3dMs }, { "contours", t.contoursMs },
    { "visibility", t.visibilityMs }, { "match_2d", t.match2dMs }, { "outliers", t.outliersMs },
    { "update", t.updateMs }, { "constraint", t.constraintMs } };
}

StageTimes timesFrom(const json& j)
{
  StageTimes t;
  t.match3dMs = j.value("match_3d", 0.0);
  t.contoursMs = j.value("contours", 0.0);
  t.visibilityMs = j.value("visibility", 0.0);
  t.match2dMs = j.value("match_2d", 0.0);
  t.outliersMs = j.value("outliers", 0.0);
  t.updateMs = j.value("update", 0.0);
  t.constraintMs = j.value("constraint", 0.0);
  return t;
}

json historyJson(const std::vector<IterationRecord>& history)
{
  json records = json::array();
  for (const IterationRecord& r : history)
  {
    records.push_back({ { "iteration", r.iteration }, { "with_contours", r.withContours },
      { "transform", matrixJson(r.transform.matrix()) },
      { "updated", matrixJson(r.updated.matrix()) }, { "cost", r.cost }, { "cost_3d", r.cost3d },
      { "cost_2d", r.cost2d }, { "point_inliers", r.pointInliers },
      { "contour_matches", r.contourMatches }, { "contour_inliers", r.contourInliers },
      { "residual_error_mm", r.residualErrorMm }, { "contour_error_px", r.contourErrorPx },
      { "backoff_steps", r.backoffSteps }, { "acceleration", r.acceleration },
      { "extrapolation_undone", r.extrapolationUndone }, { "times_ms", timesJson(r.times) } });
  }
  return records;
}

std::vector<IterationRecord> historyFrom(const json& records)
{
  std::vector<IterationRecord> history;
  for (const json& j : records)
  {
    IterationRecord r;
    j.at("iteration"); // required
    r.iteration = intValue(j, "iteration", 0);
    r.withContours = j.value("with_contours", false);
    const std::string what = "history, iteration " + std::to_string(r.iteration);
    r.transform = SimilarityTransform::fromMatrix(
      Eigen::Matrix4d(matrixFrom(j.at("transform"), 4, what)), 1e-6);
    r.updated =
      SimilarityTransform::fromMatrix(Eigen::Matrix4d(matrixFrom(j.at("updated"), 4, what)), 1e-6);
    r.cost = j.value("cost", 0.0);
    r.cost3d = j.value("cost_3d", 0.0);
    r.cost2d = j.value("cost_2d", 0.0);
    r.pointInliers = intValue(j, "point_inliers", 0);
    r.contourMatches = intValue(j, "contour_matches", 0);
    r.contourInliers = intValue(j, "contour_inliers", 0);
    r.residualErrorMm = j.value("residual_error_mm", 0.0);
    r.contourErrorPx = j.value("contour_error_px", 0.0);
    r.backoffSteps = intValue(j, "backoff_steps", 0);
    r.acceleration = j.value("acceleration", 0.0);
    r.extrapolationUndone = j.value("extrapolation_undone", false);
    if (j.contains("times_ms"))
    {
      r.times = timesFrom(j.at("times_ms"));
    }
    history.push_back(r);
  }
  return history;
}

TerminationReason terminationFrom(const std::string& name)
{
  for (TerminationReason reason :
    { TerminationReason::Converged, TerminationReason::Stalled, TerminationReason::MaxIterations,
      TerminationReason::Cancelled, TerminationReason::NumericalFailure })
  {
    if (name == toString(reason))
    {
      return reason;
    }
  }
  throw Error("unknown termination '" + name + "'");
}

vtkSmartPointer<vtkPolyData> pointCloud(const std::vector<Eigen::Vector3d>& points)
{
  vtkNew<vtkPoints> coordinates;
  coordinates->SetDataTypeToDouble();
  vtkNew<vtkCellArray> vertices;
  for (const Eigen::Vector3d& p : points)
  {
    const vtkIdType id = coordinates->InsertNextPoint(p.data());
    vertices->InsertNextCell(1, &id);
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(coordinates);
  polyData->SetVerts(vertices);
  return polyData;
}

void writeTable(vtkTable* table, const fs::path& path)
{
  detail::writeTableFile(table, path.string());
}

vtkSmartPointer<vtkTable> readTable(const fs::path& path)
{
  if (!fs::exists(path))
  {
    throwFileError(path.string(), "no such file");
  }
  vtkNew<vtkXMLTableReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  vtkTable* table = reader->GetOutput();
  if (!table || table->GetNumberOfColumns() == 0)
  {
    throwFileError(path.string(), "not a readable VTK table");
  }
  return table;
}

/// A polydata file that may hold no points (no contours, no matches).
vtkSmartPointer<vtkPolyData> readPossiblyEmpty(const fs::path& path)
{
  if (!fs::exists(path))
  {
    throwFileError(path.string(), "no such file");
  }
  vtkNew<vtkXMLPolyDataReader> reader;
  if (!reader->CanReadFile(path.string().c_str()))
  {
    throwFileError(path.string(), "not a VTK XML polydata file");
  }
  reader->SetFileName(path.string().c_str());
  reader->Update();
  vtkSmartPointer<vtkPolyData> polyData = reader->GetOutput();
  return polyData;
}

} // namespace

std::string resultFrameImageName(int frameId)
{
  char name[64];
  std::snprintf(name, sizeof name, "frames/frame-%04d.png", frameId);
  return name;
}

const char* resultFormatName()
{
  return "vimlop-result";
}

int resultFormatVersion()
{
  return 1;
}

void writeRegistrationRecord(const RegistrationRecord& record, const std::string& folder)
{
  if (!record.frameTimesS.empty() && record.frameTimesS.size() != record.data.frames.size())
  {
    throw Error("a registration record with " + std::to_string(record.frameTimesS.size()) +
      " frame times for " + std::to_string(record.data.frames.size()) +
      " frames: one per frame or none");
  }
  const fs::path dir(folder);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir))
  {
    throwFileError(folder, "cannot create the folder");
  }
  const RegistrationResult& result = record.result;
  writePolyData(toPolyData(record.model), (dir / "model.vtp").string());
  writePolyData(makeSfmPointPolyData(record.data), (dir / "sfm-points.vtp").string());
  writeTable(makeFrameTable(record.data.frames), dir / "frame-table.vtt");
  writePolyData(makeContourPolyData(record.data.frames), (dir / "video-contours.vtp").string());
  writePolyData(
    makeRegisteredPointPolyData(record.data, result), (dir / "registered-points.vtp").string());
  writeTable(makeFrameResultTable(result), dir / "camera-poses.vtt");
  writePolyData(makeCorrespondencePolyData(result), (dir / "correspondences.vtp").string());

  json files = { { "model", "model.vtp" }, { "sfm_points", "sfm-points.vtp" },
    { "frame_table", "frame-table.vtt" }, { "video_contours", "video-contours.vtp" },
    { "registered_points", "registered-points.vtp" }, { "camera_poses", "camera-poses.vtt" },
    { "correspondences", "correspondences.vtp" } };

  json frames = json::array();
  for (size_t j = 0; j < record.data.frames.size(); ++j)
  {
    const VideoFrame& frame = record.data.frames[j];
    const PinholeCamera& k = frame.intrinsics;
    json f = { { "id", frame.frameId },
      { "intrinsics",
        { { "fx", k.fx }, { "fy", k.fy }, { "cx", k.cx }, { "cy", k.cy }, { "width_px", k.widthPx },
          { "height_px", k.heightPx } } },
      { "camera_to_sfm", matrixJson(frame.cameraToSfm.matrix()) } };
    if (j < result.frames.size())
    {
      const FrameResult& r = result.frames[j];
      f["camera_to_ct"] = matrixJson(r.cameraToCT.matrix());
      f["contour_points"] = r.contourPoints;
      f["matched"] = r.matched;
      f["inliers"] = r.inliers;
      f["contour_error_px"] = r.contourErrorPx;
      f["contour_error_inliers_px"] = r.contourErrorInliersPx;
      f["visible_model_samples"] = r.visibleModelSamples;
    }
    const bool hasImage = j < record.frameImages.size() && !record.frameImages[j].empty();
    f["image"] = hasImage ? json(record.frameImages[j]) : json(nullptr);
    if (j < record.frameSources.size() && !record.frameSources[j].empty())
    {
      f["source"] = record.frameSources[j];
    }
    if (j < record.frameTimesS.size())
    {
      f["time_s"] = record.frameTimesS[j];
    }
    frames.push_back(f);
  }

  int inliers = 0;
  for (char in : result.pointInliers)
  {
    inliers += in != 0;
  }
  json summary = { { "format", resultFormatName() }, { "version", resultFormatVersion() },
    { "vimlop_version", VIMLOP_VERSION }, { "source", record.source },
    { "method", toString(record.options.method) }, { "parameters", optionsJson(record.options) },
    { "initial_transform", transformJson(record.initialSfmToCT) },
    { "transform", transformJson(result.sfmToCT) }, { "termination", toString(result.termination) },
    { "iterations", result.iterations }, { "runtime_s", result.runtimeSeconds },
    { "residual_error_mm", result.residualErrorMm }, { "contour_error_px", result.contourErrorPx },
    { "contour_error_inliers_px", result.contourErrorInliersPx },
    { "points", { { "count", record.data.points.size() }, { "inliers", inliers } } },
    { "frames", frames }, { "history", historyJson(result.history) } };

  if (record.truth)
  {
    const RegistrationRecord::GroundTruth& truth = *record.truth;
    json cameras = json::array();
    json positionErrors = json::array();
    json angleErrors = json::array();
    for (size_t j = 0; j < truth.camerasCT.size(); ++j)
    {
      cameras.push_back(matrixJson(truth.camerasCT[j].matrix()));
      if (j < result.frames.size())
      {
        positionErrors.push_back(
          cameraPositionError(result.frames[j].cameraToCT, truth.camerasCT[j]));
        angleErrors.push_back(cameraAngleErrorDeg(result.frames[j].cameraToCT, truth.camerasCT[j]));
      }
    }
    json gt = { { "transform", transformJson(truth.sfmToCT) }, { "cameras_ct", cameras },
      { "camera_position_error_mm", positionErrors }, { "camera_angle_error_deg", angleErrors } };
    if (!truth.targetsCT.empty())
    {
      writePolyData(pointCloud(truth.targetsCT), (dir / "targets.vtp").string());
      gt["targets_file"] = "targets.vtp";
      gt["tre_mm"] = targetRegistrationError(result.sfmToCT, truth.sfmToCT, truth.targetsCT);
      files["targets"] = "targets.vtp";
    }
    summary["ground_truth"] = gt;
  }
  if (record.confidence)
  {
    const RegistrationRecord::Confidence& c = *record.confidence;
    summary["confidence"] = { { "failure", c.failure },
      { "failure_threshold_px", c.failureThresholdPx },
      { "failure_residual_mm", c.failureResidualMm }, { "failure_reason", c.reason },
      { "init", c.init }, { "candidates", c.candidates }, { "winner", c.winner } };
  }
  summary["versions"] = versionsJson(record);
  if (!record.commandLine.empty())
  {
    summary["command_line"] = record.commandLine;
  }
  if (!record.framesWithoutPose.empty())
  {
    json lost = json::array();
    for (const RegistrationRecord::FrameWithoutPose& f : record.framesWithoutPose)
    {
      lost.push_back({ { "id", f.frameId }, { "source", f.source },
        { "time_s", std::isfinite(f.timeS) ? json(f.timeS) : json(nullptr) } });
    }
    summary["frames_without_pose"] = lost;
  }
  if (record.runWallS > 0.0)
  {
    summary["run_wall_s"] = record.runWallS;
  }
  if (!record.inputs.empty())
  {
    summary["inputs"] = inputsJson(record);
  }
  if (!record.ctIdentity.empty())
  {
    summary["ct_identity"] = record.ctIdentity;
  }
  summary["files"] = files;
  writeFileAtomically((dir / "result.json").string(), summary.dump(2) + "\n");
}

RegistrationRecord readRegistrationRecord(const std::string& folder)
{
  const fs::path dir(folder);
  if (fs::exists(dir) && !fs::is_directory(dir))
  {
    throwFileError(folder, "not a folder (a result folder is expected)");
  }
  if (!fs::is_directory(dir))
  {
    throwFileError(folder, "no such folder");
  }
  const fs::path jsonPath = dir / "result.json";
  if (!fs::exists(jsonPath))
  {
    throwFileError(folder, "not a VIMLOP result folder (no result.json)");
  }
  json j;
  {
    std::ifstream in(jsonPath);
    try
    {
      in >> j;
    }
    catch (const json::exception& e)
    {
      throwFileError(jsonPath.string(), std::string("not valid JSON (") + e.what() + ")");
    }
  }
  // value() throws on anything but an object, and "format" may be no string.
  const json* format = j.is_object() && j.contains("format") ? &j.at("format") : nullptr;
  if (!format || !format->is_string() || format->get<std::string>() != resultFormatName())
  {
    throwFileError(jsonPath.string(),
      std::string("not a VIMLOP result (format is not '") + resultFormatName() + "')");
  }
  int version = 0;
  try
  {
    version = intValue(j, "version", 0);
  }
  catch (const Error& e)
  {
    throwFileError(jsonPath.string(), std::string(e.what()));
  }
  if (version > resultFormatVersion())
  {
    throwFileError(jsonPath.string(),
      "format version " + std::to_string(version) + " is newer than this program reads (" +
        std::to_string(resultFormatVersion()) + ")");
  }

  RegistrationRecord record;
  try
  {
    record.source = j.value("source", std::string());
    record.model = toModelMesh(readPolyData((dir / "model.vtp").string()), nullptr);
    vtkSmartPointer<vtkTable> frameTable = readTable(dir / "frame-table.vtt");
    record.data = toRegistrationData(readPolyData((dir / "sfm-points.vtp").string()), frameTable,
      readPossiblyEmpty(dir / "video-contours.vtp"), 1.0);
    record.options = optionsFrom(j.at("parameters"));
    record.initialSfmToCT = transformFrom(j.at("initial_transform"), "initial_transform");

    RegistrationResult& result = record.result;
    result.sfmToCT = transformFrom(j.at("transform"), "transform");
    result.termination = terminationFrom(j.at("termination").get<std::string>());
    result.iterations = intValue(j, "iterations", 0);
    result.runtimeSeconds = j.value("runtime_s", 0.0);
    result.residualErrorMm = j.value("residual_error_mm", 0.0);
    result.contourErrorPx = j.value("contour_error_px", 0.0);
    result.contourErrorInliersPx = j.value("contour_error_inliers_px", 0.0);
    result.history = historyFrom(j.at("history"));
    const json& frames = j.at("frames");
    if (frames.size() != record.data.frames.size())
    {
      throw Error("result.json lists " + std::to_string(frames.size()) +
        " frames but the frame table has " + std::to_string(record.data.frames.size()));
    }
    for (size_t f = 0; f < frames.size(); ++f)
    {
      const json& fj = frames[f];
      const std::string image = fj.contains("image") && fj.at("image").is_string()
        ? fj.at("image").get<std::string>()
        : std::string();
      record.frameImages.push_back(image);
      record.frameSources.push_back(fj.contains("source") && fj.at("source").is_string()
          ? fj.at("source").get<std::string>()
          : std::string());
      if (fj.contains("time_s"))
      {
        const json& time = fj.at("time_s");
        if (!time.is_number() || !std::isfinite(time.get<double>()))
        {
          throw Error("frame " + std::to_string(f) + "'s time_s is not a finite number of seconds");
        }
        record.frameTimesS.push_back(time.get<double>());
      }
      if (!fj.contains("camera_to_ct"))
      {
        continue;
      }
      FrameResult r;
      fj.at("id"); // required
      r.frameId = intValue(fj, "id", 0);
      r.cameraToCT = CameraPose::fromMatrix(
        Eigen::Matrix4d(matrixFrom(fj.at("camera_to_ct"), 4, "camera_to_ct")));
      r.contourPoints = intValue(fj, "contour_points", 0);
      r.matched = intValue(fj, "matched", 0);
      r.inliers = intValue(fj, "inliers", 0);
      r.contourErrorPx = fj.value("contour_error_px", 0.0);
      r.contourErrorInliersPx = fj.value("contour_error_inliers_px", 0.0);
      r.visibleModelSamples = intValue(fj, "visible_model_samples", 0);
      result.frames.push_back(std::move(r));
    }
    if (!record.frameTimesS.empty() && record.frameTimesS.size() != frames.size())
    {
      throw Error("result.json gives time_s for " + std::to_string(record.frameTimesS.size()) +
        " of its " + std::to_string(frames.size()) + " frames: on every frame or on none");
    }
    readRegisteredPoints(readPolyData((dir / "registered-points.vtp").string()),
      static_cast<int>(record.data.points.size()), result);
    readCorrespondences(readPossiblyEmpty(dir / "correspondences.vtp"), result);

    if (j.contains("ground_truth"))
    {
      const json& gt = j.at("ground_truth");
      RegistrationRecord::GroundTruth truth;
      truth.sfmToCT = transformFrom(gt.at("transform"), "ground_truth.transform");
      for (const json& camera : gt.at("cameras_ct"))
      {
        truth.camerasCT.push_back(CameraPose::fromMatrix(
          Eigen::Matrix4d(matrixFrom(camera, 4, "ground_truth.cameras_ct"))));
      }
      if (gt.contains("targets_file"))
      {
        vtkSmartPointer<vtkPolyData> targets =
          readPolyData((dir / gt.at("targets_file").get<std::string>()).string());
        for (vtkIdType i = 0; i < targets->GetNumberOfPoints(); ++i)
        {
          Eigen::Vector3d p;
          targets->GetPoint(i, p.data());
          truth.targetsCT.push_back(p);
        }
      }
      record.truth = std::move(truth);
    }
    if (j.contains("confidence"))
    {
      const json& cj = j.at("confidence");
      RegistrationRecord::Confidence c;
      c.failure = cj.at("failure").get<bool>();
      c.failureThresholdPx = cj.value("failure_threshold_px", 0.0);
      c.failureResidualMm = cj.value("failure_residual_mm", 0.0);
      c.reason = cj.value("failure_reason", std::string());
      c.init = cj.value("init", std::string());
      c.candidates = cj.value("candidates", 1);
      c.winner = cj.value("winner", 0);
      record.confidence = c;
    }
    if (j.contains("inputs"))
    {
      for (const json& input : j.at("inputs"))
      {
        record.inputs.push_back(
          { input.at("role").get<std::string>(), input.at("path").get<std::string>(),
            input.at("bytes").get<std::uint64_t>(), input.at("sha256").get<std::string>() });
      }
    }
    record.commandLine = j.value("command_line", std::string());
    if (j.contains("frames_without_pose"))
    {
      for (const json& f : j.at("frames_without_pose"))
      {
        RegistrationRecord::FrameWithoutPose lost;
        lost.frameId = f.at("id").get<int>();
        lost.source = f.value("source", std::string());
        if (f.contains("time_s") && f.at("time_s").is_number())
        {
          lost.timeS = f.at("time_s").get<double>();
        }
        record.framesWithoutPose.push_back(lost);
      }
    }
    record.runWallS = j.value("run_wall_s", 0.0);
    if (j.contains("ct_identity"))
    {
      record.ctIdentity = j.at("ct_identity").get<std::map<std::string, std::string>>();
    }
    if (j.contains("versions") && j.at("versions").is_object())
    {
      for (const auto& [name, version] : j.at("versions").items())
      {
        if (name != "vimlop" && version.is_string())
        {
          record.versions[name] = version.get<std::string>();
        }
      }
    }
  }
  catch (const json::exception& e)
  {
    throwFileError(jsonPath.string(), std::string(e.what()));
  }
  catch (const Error& e)
  {
    const std::string message = e.what();
    // File errors already name their file; others are about this folder.
    throw Error(message.rfind("'", 0) == 0 ? message : "'" + folder + "': " + message);
  }
  return record;
}

} // namespace vimlop
