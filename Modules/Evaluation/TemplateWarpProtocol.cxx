#include <vimlop/Evaluation/TemplateWarpProtocol.h>

#include <vimlop/Core/CanonicalPoses.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/SimilarityEstimation.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TextFormat.h>
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

/// Step (mm) of the frame points that carry a pose's orientation through a
/// map known only at points (the truth, elastix's).
constexpr double kFrameStepMm = 1.0;

/// Four points per pose: its centre and the centre 1 mm along each CT axis.
std::vector<Point> framePoints(const std::vector<CameraPose>& poses)
{
  std::vector<Point> points;
  for (const CameraPose& pose : poses)
  {
    for (int a = -1; a < 3; ++a)
    {
      Eigen::Vector3d p = pose.centre;
      if (a >= 0)
      {
        p[a] += kFrameStepMm;
      }
      points.push_back({ p.x(), p.y(), p.z() });
    }
  }
  return points;
}

/// The poses carried by a map, from their frame points' images (from
/// `first` on): the centre's image, and the rotation part of the map's
/// Jacobian from forward differences, as warpCameraPose() turns them.
std::vector<CameraPose> carriedPoses(
  const std::vector<CameraPose>& poses, const std::vector<Point>& images, std::size_t first)
{
  std::vector<CameraPose> carried;
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    auto image = [&](std::size_t k)
    {
      const Point& p = images[first + 4 * i + k];
      return Eigen::Vector3d(p[0], p[1], p[2]);
    };
    Eigen::Matrix3d jacobian;
    for (int a = 0; a < 3; ++a)
    {
      jacobian.col(a) = (image(static_cast<std::size_t>(a) + 1) - image(0)) / kFrameStepMm;
    }
    CameraPose pose;
    pose.centre = image(0);
    pose.rotation = nearestRotation(jacobian) * poses[i].rotation;
    carried.push_back(pose);
  }
  return carried;
}

PoseErrorSummary summarizePoseErrors(const std::vector<CameraPose>& estimate,
  const std::vector<CameraPose>& truth, const std::vector<CameraPose>& templatePoses,
  const RegistrationModel& templateModel)
{
  PoseErrorSummary s;
  s.poses = truth.size();
  if (truth.empty())
  {
    return s;
  }
  std::vector<double> mm(truth.size());
  std::vector<double> deg(truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i)
  {
    mm[i] = cameraPositionError(estimate[i], truth[i]);
    deg[i] = cameraAngleErrorDeg(estimate[i], truth[i]);
  }
  const std::size_t worst =
    static_cast<std::size_t>(std::max_element(deg.begin(), deg.end()) - deg.begin());
  const Eigen::Vector3d at = templatePoses[worst].centre;
  s.maxDegAtMm = { at.x(), at.y(), at.z() };
  s.maxDegWallDistanceMm = templateModel.locator().closestPoint(at).distanceMm;
  const Summary position = summarize(mm);
  const Summary orientation = summarize(deg);
  s.meanMm = position.mean;
  s.p95Mm = position.p95;
  s.maxMm = position.max;
  s.meanDeg = orientation.mean;
  s.p95Deg = orientation.p95;
  s.maxDeg = orientation.max;
  return s;
}

/// Radius (mm) of the walls that turn a pose in WallOrientationSummary, and
/// the fewest vertices that do.
constexpr double kWallRadiusMm = 15.0;
constexpr std::size_t kFewestWallVertices = 10;

/// Per pose, the scored vertices within kWallRadiusMm of its centre (none
/// when fewer than kFewestWallVertices).
std::vector<std::vector<std::size_t>> wallsAround(const std::vector<CameraPose>& poses,
  const std::vector<Point>& vertices, const std::vector<std::size_t>& scored)
{
  std::vector<std::vector<std::size_t>> walls(poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k)
  {
    for (std::size_t i : scored)
    {
      const Eigen::Vector3d v(vertices[i][0], vertices[i][1], vertices[i][2]);
      if ((v - poses[k].centre).norm() <= kWallRadiusMm)
      {
        walls[k].push_back(i);
      }
    }
    if (walls[k].size() < kFewestWallVertices)
    {
      walls[k].clear();
    }
  }
  return walls;
}

/// The pose's orientation turned by the rotation that best carries its walls
/// to their images.
Eigen::Matrix3d turnedByWalls(const CameraPose& pose, const std::vector<std::size_t>& walls,
  const std::vector<Point>& vertices, const std::vector<Point>& images)
{
  std::vector<Eigen::Vector3d> from, to;
  for (std::size_t i : walls)
  {
    from.emplace_back(vertices[i][0], vertices[i][1], vertices[i][2]);
    to.emplace_back(images[i][0], images[i][1], images[i][2]);
  }
  return estimateSimilarity(from, to).rotation * pose.rotation;
}

/// The angles between two orientations of each pose that has walls; a null
/// `imagesB` takes `rotationsB` instead of turning by B's images.
WallOrientationSummary compareOrientations(const std::vector<CameraPose>& poses,
  const std::vector<std::vector<std::size_t>>& walls, const std::vector<Point>& vertices,
  const std::vector<Point>& imagesA, const std::vector<Point>* imagesB,
  const std::vector<CameraPose>& rotationsB)
{
  std::vector<double> deg;
  for (std::size_t k = 0; k < poses.size(); ++k)
  {
    if (walls[k].empty())
    {
      continue;
    }
    CameraPose a = poses[k];
    CameraPose b = rotationsB[k];
    a.rotation = turnedByWalls(poses[k], walls[k], vertices, imagesA);
    if (imagesB)
    {
      b.rotation = turnedByWalls(poses[k], walls[k], vertices, *imagesB);
    }
    a.centre = b.centre;
    deg.push_back(cameraAngleErrorDeg(a, b));
  }
  WallOrientationSummary s;
  s.poses = deg.size();
  if (!deg.empty())
  {
    const Summary summary = summarize(deg);
    s.meanDeg = summary.mean;
    s.p95Deg = summary.p95;
    s.maxDeg = summary.max;
  }
  return s;
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
  const std::vector<Point> poseFrames = framePoints(poses);
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
  const std::vector<std::vector<std::size_t>> walls = wallsAround(poses, vertices, scored);
  r.poseErrors.byWalls = compareOrientations(poses, walls, vertices, warped, &truth, truePoses);
  r.truthWallsAgainstJacobian =
    compareOrientations(poses, walls, vertices, truth, nullptr, truePoses);

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
    e.poseErrors.byWalls =
      compareOrientations(poses, walls, vertices, movedVertices, &truth, truePoses);
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
