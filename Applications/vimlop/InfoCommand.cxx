#include "CommandLine.h"
#include "Commands.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Video/IntrinsicsIO.h>

#include <CLI/CLI.hpp>

#include <vtkPolyData.h>

#include <algorithm>
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
};

void printCT(const std::string& path, const CTReadOptions& options)
{
  const CTVolume v = readCTVolume(path, options);
  for (const std::string& warning : v.warnings)
  {
    std::cerr << "vimlop info: warning: " << warning << "\n";
  }
  const auto [lo, hi] = std::minmax_element(v.intensities.begin(), v.intensities.end());
  std::printf("file:        %s\n", path.c_str());
  std::printf("kind:        CT volume (%s)\n", v.format.c_str());
  std::printf("dimensions:  %d x %d x %d voxels\n", v.dims[0], v.dims[1], v.dims[2]);
  std::printf(
    "spacing:     %.4f x %.4f x %.4f mm\n", v.spacingMm[0], v.spacingMm[1], v.spacingMm[2]);
  std::printf("size:        %.1f x %.1f x %.1f mm\n", v.spacingMm[0] * (v.dims[0] - 1),
    v.spacingMm[1] * (v.dims[1] - 1), v.spacingMm[2] * (v.dims[2] - 1));
  std::printf(
    "origin:      (%.3f, %.3f, %.3f) mm, LPS\n", v.originMm[0], v.originMm[1], v.originMm[2]);
  for (int row = 0; row < 3; ++row)
  {
    std::printf("%s [%7.4f %7.4f %7.4f]\n", row == 0 ? "direction:  " : "            ",
      v.direction[3 * row], v.direction[3 * row + 1], v.direction[3 * row + 2]);
  }
  std::printf("intensity:   %.0f .. %.0f\n", static_cast<double>(*lo), static_cast<double>(*hi));
}

void printMesh(const std::string& path)
{
  const vtkSmartPointer<vtkPolyData> polyData = readPolyData(path);
  std::printf("file:        %s\n", path.c_str());
  std::printf("kind:        surface mesh\n");
  std::printf("points:      %lld\n", static_cast<long long>(polyData->GetNumberOfPoints()));
  std::printf("polygons:    %lld\n", static_cast<long long>(polyData->GetNumberOfPolys()));
  double b[6];
  polyData->GetBounds(b);
  std::printf("bounds:      x %.2f .. %.2f, y %.2f .. %.2f, z %.2f .. %.2f mm\n", b[0], b[1], b[2],
    b[3], b[4], b[5]);
  if (polyData->GetNumberOfPolys() > 0)
  {
    TriangleMesh mesh;
    try
    {
      mesh = toTriangleMesh(polyData);
    }
    catch (const Error& e)
    {
      throw Error("'" + path + "': " + e.what());
    }
    std::printf("triangles:   %d\n", mesh.numberOfFaces());
    std::printf("area:        %.1f mm^2\n", mesh.totalArea());
    std::printf("open edges:  %d\n", mesh.numberOfBoundaryEdges());
    std::printf("non-manifold edges: %d\n", mesh.numberOfNonManifoldEdges());
  }
}

void printIntrinsics(const std::string& path)
{
  const PinholeCamera k = readIntrinsics(path);
  std::printf("file:        %s\n", path.c_str());
  std::printf("kind:        camera intrinsics\n");
  std::printf("image:       %d x %d pixels\n", k.widthPx, k.heightPx);
  std::printf("focal:       fx %.3f, fy %.3f pixels\n", k.fx, k.fy);
  std::printf("principal:   cx %.3f, cy %.3f pixels\n", k.cx, k.cy);
  std::printf("distortion:  ");
  if (k.distortion.size() == 0)
  {
    std::printf("none");
  }
  else if (k.lensModel == LensModel::Fisheye)
  {
    std::printf("fisheye ");
  }
  for (Eigen::Index i = 0; i < k.distortion.size(); ++i)
  {
    std::printf("%s%g", i ? ", " : "", k.distortion[i]);
  }
  std::printf("\n");
}

void runInfo(const InfoOptions& options)
{
  const std::string& path = options.path;
  if (isCTVolumePath(path))
  {
    printCT(path, options.ct);
  }
  else if (isMeshPath(path))
  {
    printMesh(path);
  }
  else if (isIntrinsicsPath(path))
  {
    printIntrinsics(path);
  }
  else
  {
    throw Error("'" + path +
      "': unsupported file type (CT: .inv3 .nii .nii.gz .nrrd .nhdr .mha .mhd .dcm or a DICOM "
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
  info->callback([options] { runInfo(*options); });
}

} // namespace vimlop
