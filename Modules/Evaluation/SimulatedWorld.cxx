#include <vimlop/Evaluation/SimulatedWorld.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/MeshTree.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/SyntheticDeformation.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Imaging/TemplateRegistration.h>
#include <vimlop/Imaging/TemplateWarp.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <nlohmann/json.hpp>

#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

namespace vimlop
{

namespace
{

void requireRange(double value, double min, double max, const char* what, const char* unit)
{
  if (!(value >= min && value <= max))
  {
    throw Error(formatText("the %s must lie in [%g, %g] %s, not %g", what, min, max, unit, value));
  }
}

/// The airway surface of `ct` segmented at `thresholdHU`, with `triangles` (0: all).
vtkSmartPointer<vtkPolyData> airwaySurface(const CTVolume& ct, AirwaySegmentationOptions seg,
  AirwaySurfaceOptions surface, const std::string& what, const EvaluationProgress& progress)
{
  reportEvaluationNote(progress, "world: segmenting " + what);
  const AirwaySegmentation airway = AirwaySegmentation::compute(ct, seg);
  return AirwaySurface::compute(airway.label, surface).surface;
}

std::array<double, 6> boundsOf(const TriangleMesh& mesh)
{
  const Eigen::Matrix<double, 3, 2> b = mesh.bounds();
  return { b(0, 0), b(0, 1), b(1, 0), b(1, 1), b(2, 0), b(2, 1) };
}

void swell(SimulatedWorld& world, const MucosalSwellingOptions& swelling)
{
  if (swelling.isOff())
  {
    return;
  }
  const SwollenSurface swollen = swellMucosa(world.truth, swelling);
  world.truth = swollen.mesh;
  world.swellingMaxMm =
    *std::max_element(swollen.displacementMm.begin(), swollen.displacementMm.end());
  world.swollenAreaMm2 = swollen.swollenAreaMm2;
  world.notes.push_back(formatText("swelling: up to %.2f mm over %.0f mm^2 of the nasal cavity",
    world.swellingMaxMm, world.swollenAreaMm2));
}

nlohmann::json distancesJson(const SurfaceDistanceSummary& s)
{
  return { { "mean_mm", s.meanMm }, { "median_mm", s.medianMm }, { "p95_mm", s.p95Mm },
    { "max_mm", s.maxMm } };
}

} // namespace

bool SimulatedWorldOptions::isIdealWorld() const
{
  return !this->needsCT() && this->swelling.isOff();
}

bool SimulatedWorldOptions::needsCT() const
{
  return this->anatomyDeformationMm != 0.0 || this->segmentationOffsetHU != 0.0 ||
    this->truthTriangles != this->surface.targetTriangles;
}

void SimulatedWorldOptions::requireMeshWorld() const
{
  if (this->needsCT())
  {
    throw Error("this model error (a deformation, a segmentation offset or a finer truth) needs "
                "the CT (--ct), not a mesh");
  }
}

void SimulatedWorldOptions::validate() const
{
  requireRange(this->anatomyDeformationMm, 0.0, 20.0, "anatomy's deformation", "mm");
  requireRange(this->anatomyControlSpacingMm, 5.0, 200.0, "deformation's control spacing", "mm");
  requireRange(this->patientNoiseHU, 0.0, 500.0, "patient CT's noise", "HU");
  requireRange(this->segmentationOffsetHU, -300.0, 300.0, "segmentation offset", "HU");
  if (this->truthTriangles < 0)
  {
    throw Error("the truth surface's triangle count must not be negative (0: all), not " +
      std::to_string(this->truthTriangles));
  }
  this->swelling.validate();
  this->canonical.validate();
}

SurfaceDistanceSummary surfaceDistances(const TriangleMesh& truth, const TriangleMesh& model)
{
  SurfaceDistanceSummary s;
  if (truth.numberOfVertices() == 0 || model.numberOfFaces() == 0)
  {
    return s;
  }
  const MeshTree tree(model);
  std::vector<double> d;
  d.reserve(truth.vertices().size());
  double sum = 0.0;
  for (const Eigen::Vector3d& v : truth.vertices())
  {
    d.push_back(tree.closestPoint(v).distanceMm);
    sum += d.back();
  }
  std::sort(d.begin(), d.end());
  const auto rank = [&](double q)
  { return d[std::min(d.size() - 1, static_cast<std::size_t>(std::ceil(q * d.size())) - 1)]; };
  s.meanMm = sum / static_cast<double>(d.size());
  s.medianMm = rank(0.5);
  s.p95Mm = rank(0.95);
  s.maxMm = d.back();
  return s;
}

nlohmann::json SimulatedWorld::toJson() const
{
  nlohmann::json j;
  j["truth_vertices"] = this->truth.numberOfVertices();
  j["model_vertices"] = this->model.numberOfVertices();
  j["truth_to_model"] = distancesJson(this->truthToModel);
  j["canonical_poses_from_template"] = this->canonicalPosesCT.size();
  j["warp_error_mean_mm"] = this->warpErrorMeanMm;
  j["warp_error_max_mm"] = this->warpErrorMaxMm;
  j["warp_s"] = this->warpSeconds;
  j["swelling_max_mm"] = this->swellingMaxMm;
  j["swollen_area_mm2"] = this->swollenAreaMm2;
  j["notes"] = this->notes;
  return j;
}

SimulatedWorld makeSimulatedWorld(const TriangleMesh& airway, const SimulatedWorldOptions& o)
{
  o.validate();
  o.requireMeshWorld();
  SimulatedWorld world;
  world.model = airway;
  world.truth = airway;
  swell(world, o.swelling);
  world.truthToModel = surfaceDistances(world.truth, world.model);
  return world;
}

SimulatedWorld makeSimulatedWorld(
  const CTVolume& ct, const SimulatedWorldOptions& o, const EvaluationProgress& progress)
{
  o.validate();
  SimulatedWorld world;
  // The template's airway: the model when the template is the patient.
  const vtkSmartPointer<vtkPolyData> templateSurface =
    airwaySurface(ct, o.segmentation, o.surface, "the template", progress);
  const TriangleMesh templateMesh = toTriangleMesh(templateSurface);

  AirwaySegmentationOptions truthSegmentation = o.segmentation;
  truthSegmentation.airThresholdHU += o.segmentationOffsetHU;
  AirwaySurfaceOptions truthSurface = o.surface;
  truthSurface.targetTriangles = o.truthTriangles;

  if (o.anatomyDeformationMm == 0.0)
  {
    world.model = templateMesh;
    world.truth = o.needsCT()
      ? toTriangleMesh(airwaySurface(ct, truthSegmentation, truthSurface, "the truth", progress))
      : templateMesh;
  }
  else
  {
    // The patient: the template deformed by a known field, as P4 makes it.
    SyntheticDeformationOptions field;
    field.maxDisplacementMm = o.anatomyDeformationMm;
    field.controlSpacingMm = o.anatomyControlSpacingMm;
    field.seed = o.anatomySeed;
    field.regionMm = boundsOf(templateMesh);
    reportEvaluationNote(progress, "world: deforming the anatomy");
    const SyntheticDeformation deformation(ct, field);
    const CTVolume patient = deformation.makePatient(ct, o.patientNoiseHU, o.anatomySeed + 1000u);
    world.truth = toTriangleMesh(
      airwaySurface(patient, truthSegmentation, truthSurface, "the patient", progress));

    // The model: the template's airway through VIMLOP's own registration,
    // which never sees the truth surface or the field.
    reportEvaluationNote(progress, "world: registering the template to the patient");
    TemplateRegistrationOptions registration;
    registration.regionMm = field.regionMm;
    const auto start = std::chrono::steady_clock::now();
    const TemplateRegistration warp = TemplateRegistration::compute(ct, patient, registration,
      [&](double fraction, const std::string& step)
      {
        reportEvaluationCount(
          progress, "world: " + step, static_cast<int>(std::lround(1000.0 * fraction)), 1000);
      });
    world.warpSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    world.model = toTriangleMesh(warpSurface(templateSurface, warp.templateToPatient));
    for (const std::string& w : warp.warnings)
    {
      world.notes.push_back("template registration: " + w);
    }
    double sum = 0.0;
    for (int i = 0; i < templateMesh.numberOfVertices(); ++i)
    {
      const Eigen::Vector3d& x = templateMesh.vertices()[i];
      const std::array<double, 3> truthPoint =
        deformation.templateToPatient({ x.x(), x.y(), x.z() });
      const double e =
        (world.model.vertices()[i] - Eigen::Vector3d(truthPoint[0], truthPoint[1], truthPoint[2]))
          .norm();
      sum += e;
      world.warpErrorMaxMm = std::max(world.warpErrorMaxMm, e);
    }
    world.warpErrorMeanMm = sum / templateMesh.numberOfVertices();
    world.notes.push_back(
      formatText("template warp: mean vertex error %.2f mm (max %.2f) in %.1f s",
        world.warpErrorMeanMm, world.warpErrorMaxMm, world.warpSeconds));

    // The canonical poses are the template's, carried the same way (V13 b).
    const RegistrationModel templateModel = makeEmbreeRegistrationModel(templateMesh);
    for (const CameraPose& pose : makeCanonicalPoses(templateModel, o.canonical))
    {
      world.canonicalPosesCT.push_back(warpCameraPose(pose, warp.templateToPatient));
    }
  }
  swell(world, o.swelling);
  world.truthToModel = surfaceDistances(world.truth, world.model);
  world.notes.push_back(formatText("truth to model: mean %.3f mm, p95 %.3f mm, max %.3f mm",
    world.truthToModel.meanMm, world.truthToModel.p95Mm, world.truthToModel.maxMm));
  for (const std::string& note : world.notes)
  {
    reportEvaluationNote(progress, "world: " + note);
  }
  return world;
}

void writeSimulatedWorld(const SimulatedWorld& world, const std::string& folder)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(fs::path(folder) / "truth", ec);
  if (ec)
  {
    throwFileError(folder, "cannot create the folder (" + ec.message() + ")");
  }
  writePolyData(toPolyData(world.model), (fs::path(folder) / "model.vtp").string());
  if (!world.canonicalPosesCT.empty())
  {
    std::vector<FramePose> poses;
    for (std::size_t i = 0; i < world.canonicalPosesCT.size(); ++i)
    {
      poses.push_back({ static_cast<int>(i), world.canonicalPosesCT[i] });
    }
    writeFramePoses(poses, (fs::path(folder) / "canonical-poses.json").string());
  }
  writePolyData(toPolyData(world.truth), (fs::path(folder) / "truth" / "surface.vtp").string());
  writeFileAtomically(
    (fs::path(folder) / "truth" / "world.json").string(), world.toJson().dump(2) + "\n");
}

} // namespace vimlop
