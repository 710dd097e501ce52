#include <vimlop/Evaluation/TemplateWarpProtocol.h>

#include <vimlop/Core/CanonicalPoses.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/CarriedPoseErrors.h>
#include <vimlop/Evaluation/Peers/ElastixParameterFiles.h>
#include <vimlop/Evaluation/Peers/ElastixRegistration.h>
#include <vimlop/Evaluation/SyntheticDeformation.h>
#include <vimlop/Imaging/AirwaySegmentation.h>
#include <vimlop/Imaging/AirwaySurface.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Imaging/TemplateRegistration.h>
#include <vimlop/Imaging/TemplateWarp.h>
#include <vimlop/Imaging/TemplateWarpJob.h>
#include <vimlop/Imaging/VolumeCrop.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

namespace vimlop
{

namespace
{

using Point = std::array<double, 3>;

/// Per-vertex errors and the index of the vertex with the largest.
VertexErrorSummary summarizeErrors(
  const std::vector<Point>& estimate, const std::vector<Point>& truth, std::size_t* worst = nullptr)
{
  std::vector<double> errors(truth.size());
  double sum = 0.0;
  std::size_t largest = 0;
  for (std::size_t i = 0; i < truth.size(); ++i)
  {
    errors[i] = std::hypot(
      estimate[i][0] - truth[i][0], estimate[i][1] - truth[i][1], estimate[i][2] - truth[i][2]);
    sum += errors[i];
    largest = errors[i] > errors[largest] ? i : largest;
  }
  if (worst)
  {
    *worst = largest;
  }
  std::sort(errors.begin(), errors.end());
  VertexErrorSummary s;
  s.meanMm = sum / static_cast<double>(errors.size());
  const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(errors.size())));
  s.p95Mm = errors[std::max<std::size_t>(rank, 1) - 1];
  s.maxMm = errors.back();
  return s;
}

nlohmann::json errorsJson(const VertexErrorSummary& s)
{
  return { { "mean_mm", s.meanMm }, { "p95_mm", s.p95Mm }, { "max_mm", s.maxMm } };
}

nlohmann::json wallOrientationJson(const WallOrientationSummary& s)
{
  return { { "poses", s.poses }, { "mean_deg", s.meanDeg }, { "p95_deg", s.p95Deg },
    { "max_deg", s.maxDeg } };
}

nlohmann::json poseErrorsJson(const PoseErrorSummary& s)
{
  return { { "poses", s.poses }, { "mean_mm", s.meanMm }, { "p95_mm", s.p95Mm },
    { "max_mm", s.maxMm }, { "mean_deg", s.meanDeg }, { "p95_deg", s.p95Deg },
    { "max_deg", s.maxDeg }, { "max_deg_at_mm", s.maxDegAtMm },
    { "max_deg_wall_distance_mm", s.maxDegWallDistanceMm },
    { "by_walls", wallOrientationJson(s.byWalls) } };
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

void TemplateWarpProtocolOptions::validate() const
{
  if (!(this->maxDisplacementMm > 0.0))
  {
    throw Error("--max-displacement-mm must be positive");
  }
  if (!(this->noiseHU >= 0.0))
  {
    throw Error("--noise-hu must not be negative");
  }
  this->scan.validate();
  this->edits.validate();
  if (this->runElastix && this->elastixWorkFolder.empty())
  {
    throw Error("P4: elastix needs a work folder");
  }
}

std::string TemplateWarpProtocolReport::summaryText() const
{
  std::string text = formatText("seed %u, %.1f mm: mean %.2f mm, p95 %.2f mm, max %.2f mm, %.1f s "
                                "(before: mean %.2f mm)",
    this->seed, this->maxDisplacementMm, this->errors.meanMm, this->errors.p95Mm,
    this->errors.maxMm, this->runtimeS, this->beforeRegistration.meanMm);
  if (this->elastix)
  {
    const Elastix& e = *this->elastix;
    text += formatText("; elastix mean %.2f mm, p95 %.2f mm, max %.2f mm, %.1f s (%.2fx our time)",
      e.errors.meanMm, e.errors.p95Mm, e.errors.maxMm, e.runtimeS, e.runtimeRatio);
  }
  if (!this->edits.empty())
  {
    std::string where;
    for (const AnatomyEdit& e : this->edits)
    {
      where += (where.empty() ? " (" : ", ") + anatomyEditKindName(e.kind) + " " + e.site;
    }
    text += formatText("; %zu anatomy edits%s (%zu vertices left out)", this->edits.size(),
      this->editOptions.placement == AnatomyEditPlacement::AnatomicalSites ? (where + ")").c_str()
                                                                           : "",
      this->verticesNearEdits);
  }
  if (this->poseErrors.poses > 0)
  {
    text += formatText(
      "; %zu canonical poses: mean %.2f mm, %.2f deg, p95 %.2f mm, %.2f deg, max %.2f mm, %.2f deg",
      this->poseErrors.poses, this->poseErrors.meanMm, this->poseErrors.meanDeg,
      this->poseErrors.p95Mm, this->poseErrors.p95Deg, this->poseErrors.maxMm,
      this->poseErrors.maxDeg);
    if (this->elastix)
    {
      text += formatText(" (elastix %.2f mm, %.2f deg)", this->elastix->poseErrors.meanMm,
        this->elastix->poseErrors.meanDeg);
    }
    text += formatText("; turned by the walls: mean %.2f deg, max %.2f deg",
      this->poseErrors.byWalls.meanDeg, this->poseErrors.byWalls.maxDeg);
    if (this->elastix)
    {
      text += formatText(" (elastix %.2f deg, %.2f deg)", this->elastix->poseErrors.byWalls.meanDeg,
        this->elastix->poseErrors.byWalls.maxDeg);
    }
    text += formatText(" (the truth's walls against its Jacobian: mean %.2f deg)",
      this->truthWallsAgainstJacobian.meanDeg);
  }
  return text;
}

void TemplateWarpProtocolReport::requireErrorsAtMost(double meanMm, double p95Mm) const
{
  if (meanMm >= 0.0 && this->errors.meanMm > meanMm)
  {
    throw Error(formatText(
      "the mean vertex error %.2f mm exceeds the required %.2f mm", this->errors.meanMm, meanMm));
  }
  if (p95Mm >= 0.0 && this->errors.p95Mm > p95Mm)
  {
    throw Error(formatText("the 95th percentile vertex error %.2f mm exceeds the required %.2f mm",
      this->errors.p95Mm, p95Mm));
  }
}

void TemplateWarpProtocolReport::requireNoWorseThanElastix() const
{
  if (!this->elastix)
  {
    throw Error("elastix did not run (" + this->elastixStatus + "): nothing to compare with");
  }
  if (this->errors.meanMm > this->elastix->errors.meanMm)
  {
    throw Error(formatText("the mean vertex error %.3f mm exceeds elastix's %.3f mm",
      this->errors.meanMm, this->elastix->errors.meanMm));
  }
  if (this->elastix->runtimeRatio < 1.0)
  {
    throw Error(formatText("the registration took %.1f s, longer than elastix's %.1f s",
      this->runtimeS, this->elastix->runtimeS));
  }
}

nlohmann::json TemplateWarpProtocolReport::toJson() const
{
  nlohmann::json report;
  report["protocol"] = "P4 template warp (DESIGN section 6)";
  report["seed"] = this->seed;
  report["max_displacement_mm"] = this->maxDisplacementMm;
  report["control_spacing_mm"] = this->controlSpacingMm;
  report["noise_hu"] = this->noiseHU;
  report["vertices"] = this->vertices;
  report["airway_volume_cm3"] = this->airwayVolumeCm3;
  report["mean_mm"] = this->errors.meanMm;
  report["p95_mm"] = this->errors.p95Mm;
  report["max_mm"] = this->errors.maxMm;
  report["max_at_mm"] = this->maxAtMm;
  report["runtime_s"] = this->runtimeS;
  report["scan"] = { { "pixel_spacing_mm", this->scan.pixelSpacingMm },
    { "slice_spacing_mm", this->scan.sliceSpacingMm }, { "blur_mm", this->scan.blurMm },
    { "rotation_deg", this->scan.rotationDeg }, { "shift_mm", this->scan.shiftMm } };
  nlohmann::json placed = nlohmann::json::array();
  for (const AnatomyEdit& e : this->edits)
  {
    placed.push_back(
      { { "kind", anatomyEditKindName(e.kind) }, { "site", e.site }, { "centre_mm", e.centreMm } });
  }
  report["edits"] = { { "count", this->editOptions.count },
    { "sites",
      this->editOptions.placement == AnatomyEditPlacement::AnatomicalSites ? "anatomical"
                                                                           : "random" },
    { "radius_mm", this->editOptions.radiusMm }, { "depth_mm", this->editOptions.depthMm },
    { "placed", placed }, { "voxels_changed", this->editedVoxels },
    { "vertices_left_out", this->verticesNearEdits }, { "poses_left_out", this->posesNearEdits } };
  report["canonical_poses"] = poseErrorsJson(this->poseErrors);
  report["canonical_poses"]["truth_by_walls_against_jacobian"] =
    wallOrientationJson(this->truthWallsAgainstJacobian);
  report["before_registration"] = errorsJson(this->beforeRegistration);
  report["affine_only"] = errorsJson(this->affineOnly);
  report["registration"] = { { "affine_s", this->affineS }, { "bspline_s", this->bsplineS },
    { "syn_s", this->synS }, { "overlap_fraction", this->overlapFraction },
    { "correlation",
      { { "initial", this->initialCorrelation }, { "affine", this->affineCorrelation },
        { "final", this->finalCorrelation } } },
    { "template_crop_mm", this->templateCropMm }, { "settings", settingsJson(this->settings) } };
  if (this->elastix)
  {
    nlohmann::json e = errorsJson(this->elastix->errors);
    e["canonical_poses"] = poseErrorsJson(this->elastix->poseErrors);
    e["runtime_s"] = this->elastix->runtimeS;
    e["runtime_ratio"] = this->elastix->runtimeRatio;
    e["parameter_files"] = this->elastix->parameterFiles;
    report["elastix"] = e;
  }
  else
  {
    report["elastix"] = nullptr;
  }
  report["elastix_status"] = this->elastixStatus;
  return report;
}

TemplateWarpProtocolReport runTemplateWarpProtocol(const CTVolume& ct,
  const TemplateWarpProtocolOptions& options, const EvaluationProgress& progress)
{
  namespace fs = std::filesystem;
  options.validate();
  // The stages report fractions; the protocol counts thousandths.
  auto report = [&](double fraction, const std::string& step) {
    reportEvaluationCount(progress, step, static_cast<int>(std::lround(1000.0 * fraction)), 1000);
  };

  // The template and its airway mesh.
  const AirwaySegmentation airway = AirwaySegmentation::compute(
    ct, {}, [&](double f, const std::string& step) { report(0.03 * f, step); });
  const AirwaySurface surface = AirwaySurface::compute(airway.label, {});
  std::vector<Point> vertices(static_cast<std::size_t>(surface.surface->GetNumberOfPoints()));
  std::array<double, 6> region{ 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (std::size_t i = 0; i < vertices.size(); ++i)
  {
    surface.surface->GetPoint(static_cast<vtkIdType>(i), vertices[i].data());
    for (int a = 0; a < 3; ++a)
    {
      region[2 * a] = std::min(region[2 * a], vertices[i][a]);
      region[2 * a + 1] = std::max(region[2 * a + 1], vertices[i][a]);
    }
  }

  // The patient: a known smooth deformation plus noise.
  report(0.04, "making the patient");
  SyntheticDeformationOptions deformationOptions;
  deformationOptions.maxDisplacementMm = options.maxDisplacementMm;
  deformationOptions.controlSpacingMm = options.controlSpacingMm;
  deformationOptions.seed = options.seed;
  deformationOptions.regionMm = region;
  const SyntheticDeformation deformation(ct, deformationOptions);
  // With the template's scan, the patient is the deformed CT itself (the
  // figures before the scan options, bit for bit).
  const bool scanned = !options.scan.isTemplateGrid();
  const PatientScan scan(ct, options.scan);
  // The local edits, on the template's anatomy before the deformation.
  AnatomyEditOptions editOptions = options.edits;
  editOptions.seed = options.seed;
  const TriangleMesh templateMesh = toTriangleMesh(surface.surface);
  const std::vector<AnatomyEdit> edits =
    editOptions.placement == AnatomyEditPlacement::AnatomicalSites
    ? placeAnatomicalEdits(templateMesh, ct, editOptions)
    : placeAnatomyEdits(vertices, editOptions);
  CTVolume edited;
  std::size_t editedVoxels = 0;
  if (!edits.empty())
  {
    edited = ct;
    editedVoxels = applyAnatomyEdits(edited, edits, editOptions);
  }
  const CTVolume& anatomy = edits.empty() ? ct : edited;
  const CTVolume patient = scanned
    ? scan.scan(deformation.makePatient(anatomy, 0.0, 0u), options.noiseHU, options.seed + 1000u)
    : deformation.makePatient(anatomy, options.noiseHU, options.seed + 1000u);
  // The vertices scored: those away from every edit.
  std::vector<std::size_t> scored;
  for (std::size_t i = 0; i < vertices.size(); ++i)
  {
    if (!nearAnatomyEdit(vertices[i], edits, editOptions))
    {
      scored.push_back(i);
    }
  }
  if (scored.empty())
  {
    throw Error("the anatomy edits cover the whole airway mesh: use fewer or smaller edits");
  }
  const auto scoredOnly = [&](const std::vector<Point>& all)
  {
    std::vector<Point> some;
    some.reserve(scored.size());
    for (std::size_t i : scored)
    {
      some.push_back(all[i]);
    }
    return some;
  };
  const auto truthMap = [&](const Point& x)
  {
    const Point y = deformation.templateToPatient(x);
    return scanned ? scan.place(y) : y;
  };
  std::vector<Point> truth(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
  {
    truth[i] = truthMap(vertices[i]);
  }
  // The template's canonical poses, and where the known map carries them.
  report(0.045, "canonical poses");
  std::vector<CameraPose> poses;
  std::size_t posesNearEdits = 0;
  const auto templateModel = makeEmbreeRegistrationModel(templateMesh);
  for (const CameraPose& pose : makeCanonicalPoses(templateModel, {}))
  {
    if (nearAnatomyEdit({ pose.centre.x(), pose.centre.y(), pose.centre.z() }, edits, editOptions))
    {
      ++posesNearEdits;
      continue;
    }
    poses.push_back(pose);
  }
  const std::vector<Point> poseFrames = poseFramePoints(poses);
  std::vector<Point> poseFrameImages(poseFrames.size());
  std::transform(poseFrames.begin(), poseFrames.end(), poseFrameImages.begin(), truthMap);
  const std::vector<CameraPose> truePoses = carriedPoses(poses, poseFrameImages, 0);

  TemplateWarpProtocolReport r;
  r.seed = options.seed;
  r.maxDisplacementMm = options.maxDisplacementMm;
  r.controlSpacingMm = options.controlSpacingMm;
  r.noiseHU = options.noiseHU;
  r.scan = options.scan;
  r.editOptions = editOptions;
  r.edits = edits;
  r.editedVoxels = editedVoxels;
  r.verticesNearEdits = vertices.size() - scored.size();
  r.posesNearEdits = posesNearEdits;
  r.vertices = vertices.size();
  r.airwayVolumeCm3 = airway.volumeMm3 / 1000.0;
  const std::vector<Point> scoredTruth = scoredOnly(truth);
  r.beforeRegistration = summarizeErrors(scoredOnly(vertices), scoredTruth);

  // VIMLOP's registration.
  TemplateRegistrationOptions registration = options.registration;
  registration.regionMm = region;
  const auto start = std::chrono::steady_clock::now();
  const TemplateRegistration result = TemplateRegistration::compute(ct, patient, registration,
    [&](double f, const std::string& step) { report(0.05 + 0.6 * f, step); });
  std::vector<Point> warped(vertices.size());
  std::vector<Point> affineOnly(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
  {
    warped[i] = result.templateToPatient.transformPoint(vertices[i]);
    for (int row = 0; row < 3; ++row)
    {
      affineOnly[i][row] = result.affine[4 * row + 3];
      for (int col = 0; col < 3; ++col)
      {
        affineOnly[i][row] += result.affine[4 * row + col] * vertices[i][col];
      }
    }
  }
  r.runtimeS = secondsSince(start);
  std::vector<CameraPose> warpedPoses;
  for (const CameraPose& pose : poses)
  {
    warpedPoses.push_back(warpCameraPose(pose, result.templateToPatient));
  }
  r.poseErrors = summarizePoseErrors(warpedPoses, truePoses, poses, templateModel);
  const WallOrientations byWalls(poses, vertices, scored, truth, truePoses);
  r.poseErrors.byWalls = byWalls.errorsOf(warped);
  r.truthWallsAgainstJacobian = byWalls.truthAgainstJacobian();

  std::size_t worst = 0;
  r.errors = summarizeErrors(scoredOnly(warped), scoredTruth, &worst);
  r.maxAtMm = vertices[scored[worst]];
  r.affineOnly = summarizeErrors(scoredOnly(affineOnly), scoredTruth);
  r.affineS = result.affineSeconds;
  r.synS = result.synSeconds;
  r.bsplineS = result.bsplineSeconds;
  r.settings = result.settings;
  r.overlapFraction = result.overlapFraction;
  r.initialCorrelation = result.initialCorrelation;
  r.affineCorrelation = result.affineCorrelation;
  r.finalCorrelation = result.finalCorrelation;
  r.templateCropMm = result.templateCropMm;
  r.warnings = result.warnings;

  // elastix on the same pair: the same template crop, the patient around it.
  const std::string parameters = options.elastixParametersFolder.empty()
    ? defaultElastixParametersFolder()
    : options.elastixParametersFolder;
  ElastixRegistrationOptions elastix;
  elastix.parameterFiles = { (fs::path(parameters) / "affine.txt").string(),
    (fs::path(parameters) / "bspline.txt").string() };
  elastix.workDirectory = options.elastixWorkFolder;
  if (!options.runElastix)
  {
    r.elastixStatus = "not run (--no-elastix)";
  }
  else if (!ElastixRegistration::available(elastix))
  {
    r.elastixStatus = "not installed";
  }
  else
  {
    report(0.66, "elastix");
    constexpr float low = -1000.0f;
    constexpr float high = 2000.0f;
    std::array<double, 6> around = result.templateCropMm;
    for (int a = 0; a < 3; ++a)
    {
      around[2 * a] -= registration.marginMm;
      around[2 * a + 1] += registration.marginMm;
    }
    // The mesh's vertices, then the poses' frame points.
    std::vector<Point> points = vertices;
    points.insert(points.end(), poseFrames.begin(), poseFrames.end());
    const ElastixRegistration peer =
      ElastixRegistration::compute(cropVolume(ct, result.templateCropMm, low, high),
        cropVolume(patient, around, low, high), points, elastix);
    TemplateWarpProtocolReport::Elastix e;
    const std::vector<Point> movedVertices(
      peer.movingPoints.begin(), peer.movingPoints.begin() + static_cast<long>(vertices.size()));
    e.errors = summarizeErrors(scoredOnly(movedVertices), scoredTruth);
    e.poseErrors = summarizePoseErrors(
      carriedPoses(poses, peer.movingPoints, vertices.size()), truePoses, poses, templateModel);
    e.poseErrors.byWalls = byWalls.errorsOf(peer.movingPoints);
    e.runtimeS = peer.registrationSeconds + peer.transformSeconds;
    e.runtimeRatio = e.runtimeS / r.runtimeS;
    e.parameterFiles = elastix.parameterFiles;
    r.elastix = e;
    r.elastixStatus = "ran";
  }
  report(1.0, "done");
  return r;
}

} // namespace vimlop
