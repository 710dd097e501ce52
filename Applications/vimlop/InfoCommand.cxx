#include "CommandLine.h"
#include "Commands.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Video/IntrinsicsIO.h>

#include <CLI/CLI.hpp>

#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>
#include <memory>

namespace vimlop
{

namespace
{

struct InfoOptions
{
  std::string path;
  CTReadOptions ct;
  bool json = false;
};

CommandSummary ctInfo(const std::string& path, const CTReadOptions& options)
{
  const CTVolume v = readCTVolume(path, options);
  for (const std::string& warning : v.warnings)
  {
    std::cerr << "vimlop info: warning: " << warning << "\n";
  }
  const auto [lo, hi] = std::minmax_element(v.intensities.begin(), v.intensities.end());
  const std::array<double, 3> sizeMm{ v.spacingMm[0] * (v.dims[0] - 1),
    v.spacingMm[1] * (v.dims[1] - 1), v.spacingMm[2] * (v.dims[2] - 1) };
  CommandSummary info;
  info.lines = { "file:        " + path, "kind:        CT volume (" + v.format + ")",
    formatText("dimensions:  %d x %d x %d voxels", v.dims[0], v.dims[1], v.dims[2]),
    formatText(
      "spacing:     %.4f x %.4f x %.4f mm", v.spacingMm[0], v.spacingMm[1], v.spacingMm[2]),
    formatText("size:        %.1f x %.1f x %.1f mm", sizeMm[0], sizeMm[1], sizeMm[2]),
    formatText(
      "origin:      (%.3f, %.3f, %.3f) mm, LPS", v.originMm[0], v.originMm[1], v.originMm[2]) };
  for (int row = 0; row < 3; ++row)
  {
    info.lines.push_back(
      formatText("%s [%7.4f %7.4f %7.4f]", row == 0 ? "direction:  " : "            ",
        v.direction[3 * row], v.direction[3 * row + 1], v.direction[3 * row + 2]));
  }
  info.lines.push_back(
    formatText("intensity:   %.0f .. %.0f", static_cast<double>(*lo), static_cast<double>(*hi)));
  info.json = { { "file", path }, { "kind", "ct" }, { "format", v.format },
    { "dimensions", v.dims }, { "spacing_mm", v.spacingMm }, { "size_mm", sizeMm },
    { "origin_mm_lps", v.originMm }, { "direction_row_major", v.direction },
    { "intensity_range", { static_cast<double>(*lo), static_cast<double>(*hi) } },
    { "warnings", v.warnings } };
  return info;
}

CommandSummary meshInfo(const std::string& path)
{
  const vtkSmartPointer<vtkPolyData> polyData = readPolyData(path);
  const long long points = polyData->GetNumberOfPoints();
  const long long polygons = polyData->GetNumberOfPolys();
  std::array<double, 6> b{};
  polyData->GetBounds(b.data());
  CommandSummary info;
  info.lines = { "file:        " + path, "kind:        surface mesh",
    formatText("points:      %lld", points), formatText("polygons:    %lld", polygons),
    formatText("bounds:      x %.2f .. %.2f, y %.2f .. %.2f, z %.2f .. %.2f mm", b[0], b[1], b[2],
      b[3], b[4], b[5]) };
  info.json = { { "file", path }, { "kind", "mesh" }, { "points", points },
    { "polygons", polygons }, { "bounds_mm", b } };
  if (polygons > 0)
  {
    TriangleMesh mesh;
    try
    {
      mesh = toTriangleMesh(polyData);
    }
    catch (const Error& e)
    {
      throwFileError(path, std::string(e.what()));
    }
    info.lines.push_back(formatText("triangles:   %d", mesh.numberOfFaces()));
    info.lines.push_back(formatText("area:        %.1f mm^2", mesh.totalArea()));
    info.lines.push_back(formatText("open edges:  %d", mesh.numberOfBoundaryEdges()));
    info.lines.push_back(formatText("non-manifold edges: %d", mesh.numberOfNonManifoldEdges()));
    info.json["triangles"] = mesh.numberOfFaces();
    info.json["area_mm2"] = mesh.totalArea();
    info.json["open_edges"] = mesh.numberOfBoundaryEdges();
    info.json["non_manifold_edges"] = mesh.numberOfNonManifoldEdges();
  }
  return info;
}

CommandSummary intrinsicsInfo(const std::string& path)
{
  const PinholeCamera k = readIntrinsics(path);
  const bool fisheye = k.lensModel == LensModel::Fisheye;
  std::string distortion = k.distortion.size() == 0 ? "none" : (fisheye ? "fisheye " : "");
  for (Eigen::Index i = 0; i < k.distortion.size(); ++i)
  {
    distortion += formatText("%s%g", i ? ", " : "", k.distortion[i]);
  }
  CommandSummary info;
  info.lines = { "file:        " + path, "kind:        camera intrinsics",
    formatText("image:       %d x %d pixels", k.widthPx, k.heightPx),
    formatText("focal:       fx %.3f, fy %.3f pixels", k.fx, k.fy),
    formatText("principal:   cx %.3f, cy %.3f pixels", k.cx, k.cy), "distortion:  " + distortion };
  info.json = intrinsicsJson(k);
  info.json["file"] = path;
  info.json["kind"] = "intrinsics";
  return info;
}

void runInfo(const InfoOptions& options)
{
  const std::string& path = options.path;
  if (isCTVolumePath(path))
  {
    printSummary(ctInfo(path, options.ct), options.json);
  }
  else if (isMeshPath(path))
  {
    printSummary(meshInfo(path), options.json);
  }
  else if (isIntrinsicsPath(path))
  {
    printSummary(intrinsicsInfo(path), options.json);
  }
  else
  {
    throwFileError(path,
      "unsupported file type (CT: .inv3 .nii .nii.gz .nrrd .nhdr .mha .mhd .dcm or a DICOM "
      "folder; mesh: .vtp .vtk .stl .ply .obj; intrinsics: .yaml .yml .json .xml)");
  }
}

} // namespace

void addInfoCommand(CLI::App& app)
{
  auto options = std::make_shared<InfoOptions>();
  CLI::App* info =
    app.add_subcommand("info", "Print what a CT volume, mesh or intrinsics file holds");
  info
    ->add_option("file", options->path, "CT volume (file or DICOM folder), mesh or intrinsics file")
    ->required();
  addCTReadOptions(*info, options->ct);
  addJsonFlag(*info, options->json);
  info->callback([options] { runInfo(*options); });
}

} // namespace vimlop
