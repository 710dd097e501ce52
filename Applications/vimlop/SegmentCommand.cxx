#include "CommandLine.h"
#include "Commands.h"

#include "TerminalProgress.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/AirwaySegmentation.h>
#include <vimlop/Imaging/AirwaySurface.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/MeshIO.h>

#include <CLI/CLI.hpp>

#include <vtkPolyData.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

namespace vimlop
{

namespace
{

struct SegmentOptions
{
  std::string ct;
  CTReadOptions ctReading;
  std::string out;
  std::string labelOut;
  std::string seed;
  bool json = false;
  AirwaySegmentationOptions segmentation;
  AirwaySurfaceOptions surface;
};

/// "x,y,z" (mm) to a point; anything else is the user's error.
std::array<double, 3> parsePoint(const std::string& text, const std::string& option)
{
  std::array<double, 3> p{};
  std::istringstream in(text);
  char comma1 = 0;
  char comma2 = 0;
  std::string rest;
  if (!(in >> p[0] >> comma1 >> p[1] >> comma2 >> p[2]) || comma1 != ',' || comma2 != ',' ||
    (in >> rest))
  {
    throw Error(
      option + ": expected three numbers x,y,z in mm (CT frame, LPS), got '" + text + "'");
  }
  return p;
}

void runSegment(SegmentOptions options)
{
  const auto start = std::chrono::steady_clock::now();
  // Check what can be checked before the work.
  if (!isWritableMeshPath(options.out))
  {
    throw Error(
      "'" + options.out + "': unsupported mesh output type (expected .vtp, .vtk, .stl or .ply)");
  }
  if (!options.labelOut.empty() && !isWritableCTVolumePath(options.labelOut))
  {
    throwFileError(options.labelOut,
      "unsupported label output type (expected .nii, .nii.gz, .nrrd, .nhdr, .mha or .mhd)");
  }
  if (!options.seed.empty())
  {
    options.segmentation.seedMm = parsePoint(options.seed, "--seed-mm");
  }

  const CTVolume ct = readCTVolume(options.ct, options.ctReading);
  for (const std::string& warning : ct.warnings)
  {
    std::cerr << "vimlop segment: warning: " << warning << "\n";
  }
  const ProgressCallback progress = terminalProgress("segment");
  const AirwaySegmentation airway = AirwaySegmentation::compute(ct, options.segmentation,
    [&progress](double f, const std::string& step) { reportProgress(progress, 0.5 * f, step); });
  const AirwaySurface surface = AirwaySurface::compute(airway.label, options.surface,
    [&progress](double f, const std::string& step)
    { reportProgress(progress, 0.5 + 0.5 * f, step); });
  writePolyData(surface.surface, options.out);
  if (!options.labelOut.empty())
  {
    writeCTVolume(airway.label, options.labelOut);
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  for (const std::string& warning : surface.warnings())
  {
    std::cerr << "vimlop segment: warning: " << warning << "\n";
  }
  CommandSummary summary;
  summary.lines.push_back("vimlop segment: " + airway.summaryText());
  summary.lines.push_back(formatText("vimlop segment: %s, %.1f s -> %s",
    surface.summaryText().c_str(), seconds, options.out.c_str()));
  summary.json = { { "airway",
                     { { "volume_mm3", airway.volumeMm3 }, { "selection", airway.selection },
                       { "interior_air_components", airway.interiorAirComponents },
                       { "next_largest_volume_mm3", airway.nextLargestVolumeMm3 },
                       { "included_sinuses", airway.includedSinuses },
                       { "centroid_mm_lps", airway.centroidMm } } },
    { "surface",
      { { "triangles", surface.triangles }, { "vertices", surface.vertices },
        { "enclosed_volume_mm3", surface.enclosedVolumeMm3 }, { "area_mm2", surface.areaMm2 },
        { "open_edges", surface.boundaryEdges },
        { "non_manifold_edges", surface.nonManifoldEdges } } },
    { "seconds", seconds }, { "out", options.out }, { "label_out", options.labelOut } };
  printSummary(summary, options.json);
}

} // namespace

void addSegmentCommand(CLI::App& app)
{
  auto options = std::make_shared<SegmentOptions>();
  CLI::App* segment = app.add_subcommand("segment",
    "Segment the nasal airway of a head CT and write its surface (CT frame, LPS mm; normals "
    "into the air)");
  segment->add_option("--ct", options->ct, "CT volume: file or DICOM folder")->required();
  segment->add_option("--out", options->out, "Output surface: .vtp, .vtk, .stl or .ply")
    ->required();
  addCTReadOptions(*segment, options->ctReading);
  segment->add_option("--threshold", options->segmentation.airThresholdHU, "Air threshold in HU")
    ->capture_default_str();
  segment
    ->add_option("--body-threshold", options->segmentation.bodyThresholdHU,
      "Tissue threshold of the head mask in HU")
    ->capture_default_str();
  segment
    ->add_option("--triangles", options->surface.targetTriangles,
      "Target triangle count after decimation (0: no decimation)")
    ->capture_default_str();
  segment->add_option("--seed-mm", options->seed,
    "x,y,z: a point inside the airway (CT frame, LPS mm); default: the largest air space in the "
    "head");
  segment
    ->add_option("--sinus-distance-mm", options->segmentation.sinusInclusionDistanceMm,
      "Also include air spaces within this distance of the airway (sinuses); 0: none")
    ->capture_default_str();
  segment->add_option(
    "--label-out", options->labelOut, "Also write the airway label volume (.nii.gz, .nrrd, .mha)");
  addJsonFlag(*segment, options->json);
  segment->callback([options] { runSegment(*options); });
}

} // namespace vimlop
