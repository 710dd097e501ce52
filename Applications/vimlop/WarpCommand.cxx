#include "WarpCommand.h"

#include <vimlop/Imaging/AirwaySegmentation.h>
#include <vimlop/Imaging/AirwaySurface.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/DisplacementFieldIO.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/TemplateRegistration.h>
#include <vimlop/Imaging/TemplateWarp.h>
#include "TerminalProgress.h"

#include <CLI/CLI.hpp>

#include <nlohmann/json.hpp>

#include <vtkPolyData.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>

namespace vimlop
{

namespace
{

struct WarpOptions
{
  std::string templateCT;
  std::string patientCT;
  std::vector<std::string> templateMeshes;
  std::string templatePoses;
  std::string out;
  double marginMm = 15.0;
};

void grow(std::array<double, 6>& box, const double p[3])
{
  for (int a = 0; a < 3; ++a)
  {
    box[2 * a] = std::min(box[2 * a], p[a]);
    box[2 * a + 1] = std::max(box[2 * a + 1], p[a]);
  }
}

std::vector<double> affineRows(const TemplateRegistration& r)
{
  return std::vector<double>(r.affine.begin(), r.affine.end());
}

void runWarp(const WarpOptions& options)
{
  namespace fs = std::filesystem;
  const auto start = std::chrono::steady_clock::now();
  // Check the inputs' names before the long work.
  std::vector<std::string> meshOutputs;
  std::set<std::string> names;
  for (const std::string& mesh : options.templateMeshes)
  {
    if (!isMeshPath(mesh))
    {
      throw Error(
        "'" + mesh + "': unsupported mesh type (expected .vtp, .vtk, .stl, .ply or .obj)");
    }
    const std::string name = fs::path(mesh).stem().string() + ".vtp";
    if (!names.insert(name).second)
    {
      throw Error("two template meshes would both be written as '" + name + "'; rename one");
    }
    meshOutputs.push_back(name);
  }
  std::error_code ec;
  fs::create_directories(options.out, ec);
  if (!fs::is_directory(options.out))
  {
    throw Error("'" + options.out + "': cannot create the output folder");
  }

  const CTVolume templateCT = readCTVolume(options.templateCT);
  const CTVolume patientCT = readCTVolume(options.patientCT);
  for (const std::string& warning : templateCT.warnings)
  {
    std::cerr << "vimlop warp: warning: template: " << warning << "\n";
  }
  for (const std::string& warning : patientCT.warnings)
  {
    std::cerr << "vimlop warp: warning: patient: " << warning << "\n";
  }
  std::vector<vtkSmartPointer<vtkPolyData>> meshes;
  for (const std::string& mesh : options.templateMeshes)
  {
    meshes.push_back(readPolyData(mesh));
  }
  std::vector<FramePose> poses;
  if (!options.templatePoses.empty())
  {
    poses = readFramePoses(options.templatePoses);
  }
  const ProgressCallback progress = terminalProgress("warp");
  if (meshes.empty())
  {
    // No meshes: the template's own airway is the one to carry over.
    const AirwaySegmentation airway = AirwaySegmentation::compute(templateCT, {},
      [&](double f, const std::string& step) { reportProgress(progress, 0.05 * f, step); });
    meshes.push_back(AirwaySurface::compute(airway.label, {}).surface);
    meshOutputs.push_back("airway.vtp");
  }

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
  TemplateRegistration::Options registration;
  registration.regionMm = region;
  registration.marginMm = options.marginMm;
  const TemplateRegistration result =
    TemplateRegistration::compute(templateCT, patientCT, registration,
      [&](double f, const std::string& step) { reportProgress(progress, 0.05 + 0.95 * f, step); });
  for (const std::string& warning : result.warnings)
  {
    std::cerr << "vimlop warp: warning: " << warning << "\n";
  }

  // Outputs.
  const fs::path dir(options.out);
  nlohmann::json outputs = nlohmann::json::array();
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const std::string path = (dir / meshOutputs[m]).string();
    writePolyData(warpSurface(meshes[m], result.templateToPatient), path);
    outputs.push_back(path);
  }
  if (!poses.empty())
  {
    const std::string path = (dir / "poses.json").string();
    writeFramePoses(warpFramePoses(poses, result.templateToPatient), path);
    outputs.push_back(path);
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
      std::cerr << "vimlop warp: warning: " << outside
                << " camera centres lie outside the registered region\n";
    }
  }
  const std::string forwardPath = (dir / "template-to-patient.nii.gz").string();
  const std::string inversePath = (dir / "patient-to-template.nii.gz").string();
  writeDisplacementField(result.templateToPatient, forwardPath);
  writeDisplacementField(result.patientToTemplate, inversePath);
  outputs.push_back(forwardPath);
  outputs.push_back(inversePath);

  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json report;
  report["template_ct"] = options.templateCT;
  report["patient_ct"] = options.patientCT;
  report["frame"] = "template CT frame to patient CT frame (LPS, mm)";
  report["region_mm"] = region;
  report["template_crop_mm"] = result.templateCropMm;
  report["affine_template_to_patient"] = affineRows(result);
  report["overlap_fraction"] = result.overlapFraction;
  report["correlation"] = { { "initial", result.initialCorrelation },
    { "affine", result.affineCorrelation }, { "final", result.finalCorrelation } };
  report["metric"] = { { "affine_mattes_mi", result.affineMetricValue },
    { "syn", result.synMetricValue } };
  report["seconds"] = { { "affine", result.affineSeconds }, { "syn", result.synSeconds },
    { "total", seconds } };
  report["warnings"] = result.warnings;
  report["outputs"] = outputs;
  {
    std::ofstream out(dir / "registration.json");
    out << report.dump(2) << "\n";
  }
  std::printf(
    "vimlop warp: %zu meshes, %zu poses to the patient; correlation %.3f -> %.3f (affine) "
    "-> %.3f (SyN), %.1f s -> %s\n",
    meshes.size(), poses.size(), result.initialCorrelation, result.affineCorrelation,
    result.finalCorrelation, seconds, options.out.c_str());
}

} // namespace

void addWarpCommand(CLI::App& app)
{
  auto options = std::make_shared<WarpOptions>();
  CLI::App* warp = app.add_subcommand("warp",
    "Register a template CT to a patient CT (affine + SyN) and carry template meshes and camera "
    "poses into the patient");
  warp->add_option("--template-ct", options->templateCT, "Template CT: file or DICOM folder")
    ->required();
  warp->add_option("--patient-ct", options->patientCT, "Patient CT: file or DICOM folder")
    ->required();
  warp->add_option("--template-mesh", options->templateMeshes,
    "Mesh(es) in the template CT frame; default: the template's airway, segmented");
  warp->add_option("--template-poses", options->templatePoses,
    "Camera poses in the template CT frame (JSON, see Modules/Imaging/FramePoseIO.h)");
  warp
    ->add_option("--margin-mm", options->marginMm,
      "Margin around the meshes and poses of the registered region (mm)")
    ->capture_default_str();
  warp
    ->add_option("--out", options->out,
      "Output folder: warped meshes (.vtp), poses.json, displacement fields, registration.json")
    ->required();
  warp->callback([options] { runWarp(*options); });
}

} // namespace vimlop
