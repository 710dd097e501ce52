#include <vimlop/Imaging/TemplateWarpJob.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Imaging/AirwaySegmentation.h>
#include <vimlop/Imaging/AirwaySurface.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/DisplacementFieldIO.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/TemplateWarp.h>

#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <utility>

namespace vimlop
{

namespace
{

void grow(std::array<double, 6>& box, const double p[3])
{
  for (int a = 0; a < 3; ++a)
  {
    box[2 * a] = std::min(box[2 * a], p[a]);
    box[2 * a + 1] = std::max(box[2 * a + 1], p[a]);
  }
}

/// The output name of each template mesh, checked before the long work.
std::vector<std::string> meshOutputNames(const std::vector<std::string>& meshPaths)
{
  std::vector<std::string> outputs;
  std::set<std::string> names;
  for (const std::string& mesh : meshPaths)
  {
    if (!isMeshPath(mesh))
    {
      throw Error(
        "'" + mesh + "': unsupported mesh type (expected .vtp, .vtk, .stl, .ply or .obj)");
    }
    const std::string name = std::filesystem::path(mesh).stem().string() + ".vtp";
    if (!names.insert(name).second)
    {
      throw Error("two template meshes would both be written as '" + name + "'; rename one");
    }
    outputs.push_back(name);
  }
  return outputs;
}

} // namespace

nlohmann::json settingsJson(const TemplateRegistrationOptions& o)
{
  nlohmann::json settings = { { "region_mm", o.regionMm }, { "margin_mm", o.marginMm },
    { "affine_levels_mm", o.affineLevelSpacingMm }, { "affine_iterations", o.affineIterations },
    { "histogram_bins", o.histogramBins }, { "affine_sampling_fraction", o.affineSamplingFraction },
    { "syn_metric", templateRegistrationMetricName(o.metric) },
    { "syn_levels_mm", o.synLevelSpacingMm }, { "syn_iterations", o.synIterations },
    { "syn_learning_rate", o.synLearningRate }, { "update_field_variance", o.updateFieldVariance },
    { "total_field_variance", o.totalFieldVariance }, { "bspline_grid_mm", o.bsplineGridMm },
    { "bspline_levels_mm", o.bsplineLevelSpacingMm }, { "bspline_iterations", o.bsplineIterations },
    { "bspline_sampling_fraction", o.bsplineSamplingFraction },
    { "bspline_bending_weight_mm2", o.bsplineBendingWeightMm2 } };
  if (o.metric == TemplateRegistrationMetric::NeighborhoodCorrelation)
  {
    settings["correlation_radius_voxels"] = o.correlationRadiusVoxels;
  }
  return settings;
}

nlohmann::json TemplateWarpJobReport::toJson() const
{
  const TemplateRegistration& r = this->registration;
  nlohmann::json report;
  report["template_ct"] = this->templateCTPath;
  report["patient_ct"] = this->patientCTPath;
  report["frame"] = "template CT frame to patient CT frame (LPS, mm)";
  report["region_mm"] = this->regionMm;
  report["template_crop_mm"] = r.templateCropMm;
  report["affine_template_to_patient"] = r.affine;
  report["overlap_fraction"] = r.overlapFraction;
  report["correlation"] = { { "initial", r.initialCorrelation }, { "affine", r.affineCorrelation },
    { "final", r.finalCorrelation } };
  report["metric"] = { { "affine_mattes_mi", r.affineMetricValue }, { "syn", r.synMetricValue } };
  report["seconds"] = { { "affine", r.affineSeconds }, { "bspline", r.bsplineSeconds },
    { "syn", r.synSeconds }, { "total", this->totalSeconds } };
  report["settings"] = settingsJson(r.settings);
  report["warnings"] = r.warnings;
  report["outputs"] = this->outputPaths;
  return report;
}

TemplateWarpJobReport runTemplateWarpJob(const TemplateWarpJobOptions& options,
  const ProgressCallback& progress, const std::function<void(const std::string&)>& warning)
{
  namespace fs = std::filesystem;
  const auto start = std::chrono::steady_clock::now();
  TemplateWarpJobReport report;
  report.templateCTPath = options.templateCTPath;
  report.patientCTPath = options.patientCTPath;
  const auto warn = [&](const std::string& text)
  {
    report.warnings.push_back(text);
    if (warning)
    {
      warning(text);
    }
  };
  std::vector<std::string> meshOutputs = meshOutputNames(options.templateMeshPaths);
  std::error_code ec;
  fs::create_directories(options.outputFolder, ec);
  if (!fs::is_directory(options.outputFolder))
  {
    throwFileError(options.outputFolder, "cannot create the output folder");
  }

  const CTVolume templateCT = readCTVolume(options.templateCTPath);
  const CTVolume patientCT = readCTVolume(options.patientCTPath);
  for (const std::string& text : templateCT.warnings)
  {
    warn("template: " + text);
  }
  for (const std::string& text : patientCT.warnings)
  {
    warn("patient: " + text);
  }
  std::vector<vtkSmartPointer<vtkPolyData>> meshes;
  for (const std::string& mesh : options.templateMeshPaths)
  {
    meshes.push_back(readPolyData(mesh));
  }
  std::vector<FramePose> poses;
  if (!options.templatePosesPath.empty())
  {
    poses = readFramePoses(options.templatePosesPath);
  }
  if (meshes.empty())
  {
    // No meshes: the template's own airway is the one to carry over.
    const AirwaySegmentation airway = AirwaySegmentation::compute(templateCT, {},
      [&](double f, const std::string& step) { reportProgress(progress, 0.05 * f, step); });
    meshes.push_back(AirwaySurface::compute(airway.label, {}).surface);
    meshOutputs.push_back("airway.vtp");
  }
  report.meshCount = meshes.size();
  report.poseCount = poses.size();

  // The region to register: everything that travels, plus the margin.
  std::array<double, 6> region{ 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (const auto& mesh : meshes)
  {
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      grow(region, mesh->GetPoint(i));
    }
  }
  for (const FramePose& pose : poses)
  {
    grow(region, pose.cameraToWorld.centre.data());
  }
  report.regionMm = region;
  TemplateRegistrationOptions registration = options.registration;
  registration.regionMm = region;
  report.registration = TemplateRegistration::compute(templateCT, patientCT, registration,
    [&](double f, const std::string& step) { reportProgress(progress, 0.05 + 0.95 * f, step); });
  const TemplateRegistration& result = report.registration;
  for (const std::string& text : result.warnings)
  {
    warn(text);
  }

  // Outputs.
  const fs::path dir(options.outputFolder);
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const std::string path = (dir / meshOutputs[m]).string();
    writePolyData(warpSurface(meshes[m], result.templateToPatient), path);
    report.outputPaths.push_back(path);
  }
  if (!poses.empty())
  {
    const std::string path = (dir / "poses.json").string();
    writeFramePoses(warpFramePoses(poses, result.templateToPatient), path);
    report.outputPaths.push_back(path);
    int outside = 0;
    for (const FramePose& pose : poses)
    {
      outside += result.templateToPatient.contains({ pose.cameraToWorld.centre[0],
                   pose.cameraToWorld.centre[1], pose.cameraToWorld.centre[2] })
        ? 0
        : 1;
    }
    if (outside > 0)
    {
      warn(std::to_string(outside) + " camera centres lie outside the registered region");
    }
  }
  const std::string forwardPath = (dir / "template-to-patient.nii.gz").string();
  const std::string inversePath = (dir / "patient-to-template.nii.gz").string();
  writeDisplacementField(result.templateToPatient, forwardPath);
  writeDisplacementField(result.patientToTemplate, inversePath);
  report.outputPaths.push_back(forwardPath);
  report.outputPaths.push_back(inversePath);

  report.totalSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  {
    std::ofstream out(dir / "registration.json");
    out << report.toJson().dump(2) << "\n";
  }
  return report;
}

} // namespace vimlop
