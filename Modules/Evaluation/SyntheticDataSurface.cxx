#include <vimlop/Evaluation/SyntheticDataSurface.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/SimulatedWorld.h>
#include <vimlop/Evaluation/SyntheticDeformation.h>
#include <vimlop/Imaging/CTVolume.h>

#include <nlohmann/json.hpp>

#include <cmath>

namespace vimlop
{

const char* toString(SyntheticDataSurface surface)
{
  switch (surface)
  {
    case SyntheticDataSurface::Finer:
      return "finer";
    case SyntheticDataSurface::Threshold:
      return "threshold";
    case SyntheticDataSurface::Deformed:
      return "deformed";
    case SyntheticDataSurface::Model:
      break;
  }
  return "model";
}

SyntheticDataSurface syntheticDataSurfaceFromString(const std::string& name)
{
  for (SyntheticDataSurface s : { SyntheticDataSurface::Model, SyntheticDataSurface::Finer,
         SyntheticDataSurface::Threshold, SyntheticDataSurface::Deformed })
  {
    if (name == toString(s))
    {
      return s;
    }
  }
  throw Error("unknown data surface '" + name + "' (expected model, finer, threshold or deformed)");
}

bool SyntheticDataSurfaceOptions::needsCT() const
{
  return this->surface == SyntheticDataSurface::Finer ||
    this->surface == SyntheticDataSurface::Threshold;
}

void SyntheticDataSurfaceOptions::validate() const
{
  if (!(this->offsetHU >= -300.0 && this->offsetHU <= 300.0))
  {
    throw Error(formatText(
      "the data surface's threshold offset must lie in [-300, 300] HU, not %g", this->offsetHU));
  }
  if (!(this->deformationMm > 0.0 && this->deformationMm <= 20.0))
  {
    throw Error(formatText(
      "the data surface's deformation must lie in (0, 20] mm, not %g", this->deformationMm));
  }
  if (!(this->deformationControlSpacingMm >= 5.0 && this->deformationControlSpacingMm <= 200.0))
  {
    throw Error(formatText("the data surface's control spacing must lie in [5, 200] mm, not %g",
      this->deformationControlSpacingMm));
  }
}

nlohmann::json SyntheticDataSurfaceOptions::toJson() const
{
  nlohmann::json j = { { "data_surface", toString(this->surface) } };
  if (this->surface == SyntheticDataSurface::Threshold)
  {
    j["data_offset_hu"] = this->offsetHU;
  }
  if (this->surface == SyntheticDataSurface::Deformed)
  {
    j["data_deformation_mm"] = this->deformationMm;
    j["data_deformation_control_spacing_mm"] = this->deformationControlSpacingMm;
    j["data_deformation_seed"] = this->deformationSeed;
  }
  return j;
}

TriangleMesh deformSurface(
  const TriangleMesh& mesh, double maxDisplacementMm, double controlSpacingMm, std::uint32_t seed)
{
  if (mesh.numberOfVertices() == 0)
  {
    throw Error("cannot deform a surface without vertices");
  }
  // The field lives on a grid: 1 mm voxels over the mesh's bounds and a
  // margin, fine enough for the largest displacement to be measured at the
  // mesh's scale.
  const Eigen::Matrix<double, 3, 2> bounds = mesh.bounds();
  const double marginMm = 5.0;
  CTVolume grid;
  SyntheticDeformationOptions field;
  for (int a = 0; a < 3; ++a)
  {
    grid.originMm[a] = bounds(a, 0) - marginMm;
    grid.dims[a] = static_cast<int>(std::ceil(bounds(a, 1) - bounds(a, 0) + 2.0 * marginMm)) + 1;
    field.regionMm[2 * a] = bounds(a, 0);
    field.regionMm[2 * a + 1] = bounds(a, 1);
  }
  field.maxDisplacementMm = maxDisplacementMm;
  field.controlSpacingMm = controlSpacingMm;
  field.seed = seed;
  const SyntheticDeformation deformation(grid, field);
  std::vector<Eigen::Vector3d> vertices;
  vertices.reserve(mesh.vertices().size());
  for (const Eigen::Vector3d& v : mesh.vertices())
  {
    const std::array<double, 3> moved = deformation.templateToPatient({ v.x(), v.y(), v.z() });
    vertices.emplace_back(moved[0], moved[1], moved[2]);
  }
  return TriangleMesh(std::move(vertices), mesh.faces());
}

namespace
{

TriangleMesh deformed(const TriangleMesh& model, const SyntheticDataSurfaceOptions& o)
{
  return deformSurface(model, o.deformationMm, o.deformationControlSpacingMm, o.deformationSeed);
}

} // namespace

SyntheticSurfaces makeSyntheticSurfaces(const CTVolume& ct,
  const SyntheticDataSurfaceOptions& options, const EvaluationProgress& progress)
{
  options.validate();
  // The world's truth is the data surface: the same segmentation and
  // meshing code as the simulated worlds of P2-P5.
  SimulatedWorldOptions world;
  if (options.surface == SyntheticDataSurface::Finer)
  {
    world.truthTriangles = 0;
  }
  else if (options.surface == SyntheticDataSurface::Threshold)
  {
    world.segmentationOffsetHU = options.offsetHU;
  }
  const SimulatedWorld made = makeSimulatedWorld(ct, world, progress);
  SyntheticSurfaces surfaces;
  surfaces.model = made.model;
  if (options.needsCT())
  {
    surfaces.data = made.truth;
  }
  else if (options.surface == SyntheticDataSurface::Deformed)
  {
    surfaces.data = deformed(surfaces.model, options);
  }
  return surfaces;
}

SyntheticSurfaces makeSyntheticSurfaces(
  const TriangleMesh& model, const SyntheticDataSurfaceOptions& options)
{
  options.validate();
  if (options.needsCT())
  {
    throw Error(std::string("the data surface '") + toString(options.surface) +
      "' needs the CT (--ct), not a mesh");
  }
  SyntheticSurfaces surfaces;
  surfaces.model = model;
  if (options.surface == SyntheticDataSurface::Deformed)
  {
    surfaces.data = deformed(model, options);
  }
  return surfaces;
}

} // namespace vimlop
