#ifndef vimlop_SyntheticDataSurface_h
#define vimlop_SyntheticDataSurface_h

#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Evaluation/EvaluationProgress.h>

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>

namespace vimlop
{

struct CTVolume;

/// @brief Which surface P1 draws its data from (issue 14, item 4: P1 faithful to a wrong model).
enum class SyntheticDataSurface
{
  /// The model itself (the paper's P1).
  Model,
  /// The undecimated iso-surface of the same CT: anatomy is finer than any model.
  Finer,
  /// The CT segmented at another air threshold: a segmentation error.
  Threshold,
  /// The model deformed by a smooth random field: the anatomy has moved.
  Deformed
};

/// @brief "model", "finer", "threshold" or "deformed".
const char* toString(SyntheticDataSurface surface);

/// @throws vimlop::Error for another name: "unknown data surface 'x' (expected model, finer,
/// threshold or deformed)".
SyntheticDataSurface syntheticDataSurfaceFromString(const std::string& name);

/**
 * @brief How P1's data surface is made from the model or its CT; every
 * setting in the model's frame (CT, mm).
 */
struct SyntheticDataSurfaceOptions
{
  /// The surface (default the model: no model error).
  SyntheticDataSurface surface = SyntheticDataSurface::Model;
  /// With Threshold: the data's air threshold minus the model's, HU (default
  /// +100: -300 HU against the model's -400, so the data's walls lie a
  /// little into the tissue; the size of P5's "segmentation" source, the
  /// other way). In [-300, 300].
  double offsetHU = 100.0;
  /// With Deformed: the field's largest displacement over the airway, mm
  /// (default 0.5: the size of a CT voxel, an estimate of what a model error
  /// the registration should absorb looks like). In (0, 20].
  double deformationMm = 0.5;
  /// With Deformed: the field's control point spacing, mm (default 30, P4's).
  double deformationControlSpacingMm = 30.0;
  /// With Deformed: the field's seed (default 1).
  std::uint32_t deformationSeed = 1;

  /// @brief True when the surface needs the CT (Finer, Threshold).
  bool needsCT() const;
  /// @throws vimlop::Error naming the first value out of its range.
  void validate() const;
  /// @brief The settings for P1's JSON ("data_surface", and the kind's own parameters).
  nlohmann::json toJson() const;
};

/// @brief P1's model and the surface its data are drawn from (empty: the model).
struct SyntheticSurfaces
{
  TriangleMesh model;
  TriangleMesh data;
};

/**
 * @brief The model of `ct` (its airway as `vimlop segment` makes it) and the
 * data surface of `options`, both made by makeSimulatedWorld (SimulatedWorld.h):
 * Finer is its truth at full resolution, Threshold its truth at a
 * segmentation offset (the model's decimation), Deformed the model through
 * deformSurface(). Notes go to `progress`.
 * @throws vimlop::Error for invalid options, a CT without an airway, or on cancellation.
 */
SyntheticSurfaces makeSyntheticSurfaces(const CTVolume& ct,
  const SyntheticDataSurfaceOptions& options, const EvaluationProgress& progress);

/**
 * @brief The same for a model given as a mesh: Model or Deformed only.
 * @throws vimlop::Error for Finer or Threshold: "the data surface 'finer' needs the CT (--ct),
 * not a mesh".
 */
SyntheticSurfaces makeSyntheticSurfaces(
  const TriangleMesh& model, const SyntheticDataSurfaceOptions& options);

/**
 * @brief `mesh` with every vertex carried by a smooth random field
 * (SyntheticDeformation, as P4 makes its patients) of largest displacement
 * `maxDisplacementMm` over the mesh's bounds; the faces are kept.
 * @throws vimlop::Error for an empty mesh or invalid field settings.
 */
TriangleMesh deformSurface(
  const TriangleMesh& mesh, double maxDisplacementMm, double controlSpacingMm, std::uint32_t seed);

} // namespace vimlop

#endif
