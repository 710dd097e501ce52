#ifndef vimlop_SimulatedWorld_h
#define vimlop_SimulatedWorld_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/CanonicalPoses.h>
#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Evaluation/EvaluationProgress.h>
#include <vimlop/Evaluation/MucosalSwelling.h>
#include <vimlop/Imaging/AirwaySegmentation.h>
#include <vimlop/Imaging/AirwaySurface.h>

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief The model errors of a simulated world (issue 14): how the anatomy the
 * endoscope sees (the truth) differs from the surface the registration is
 * given (the model).
 *
 * Each knob is off by default: the truth is the model, the CT's own airway as
 * `vimlop segment` makes it, and the world is the ideal one of P1-P3.
 * Realistic values and their sources: Documentation/Simulation.md.
 */
struct SimulatedWorldOptions
{
  /// Model error from the real pipeline: the patient is the CT deformed by a
  /// smooth random B-spline field (SyntheticDeformation, as P4) whose largest
  /// displacement over the airway is this, mm, plus `patientNoiseHU` of
  /// noise. The model is then the template's airway (the CT's, decimated)
  /// carried into the patient by VIMLOP's template registration (as `vimlop
  /// warp` does), and the canonical poses are the template's carried the
  /// same way (V13 b, as the paper does). Default 0: the template is the
  /// patient. In [0, 20].
  double anatomyDeformationMm = 0.0;
  /// Control point spacing of that field, mm (default 30, P4's).
  double anatomyControlSpacingMm = 30.0;
  /// Seed of the field; the patient's noise uses seed + 1000 (default 1).
  std::uint32_t anatomySeed = 1;
  /// Noise of the patient CT, HU (default 20, P4's; only with a deformation).
  double patientNoiseHU = 20.0;
  /// Segmentation error: the truth is the patient's airway segmented at the
  /// model's air threshold plus this, HU (default 0; -100 is the issue's
  /// -500 HU against -400 HU). In [-300, 300].
  double segmentationOffsetHU = 0.0;
  /// Triangles of the truth surface (default 30000, the model's decimation:
  /// the ideal world; 0: the full iso-surface, as anatomy is finer than any
  /// model). At least 0.
  int truthTriangles = 30000;
  /// Erectile tissue: the truth's nasal mucosa swollen (default none).
  MucosalSwellingOptions swelling;
  /// How the model is segmented and meshed (defaults: `vimlop segment`'s).
  AirwaySegmentationOptions segmentation;
  AirwaySurfaceOptions surface;
  /// The template's canonical poses, with a deformation (defaults: the pipeline's).
  CanonicalPoseOptions canonical;

  /// @brief True when the truth is the model: no deformation, no segmentation
  /// offset, the model's decimation, no swelling.
  bool isIdealWorld() const;
  /// @brief True when making the world needs the CT (a deformation, a
  /// segmentation offset or a finer truth); swelling alone works on a mesh.
  bool needsCT() const;
  /**
   * @brief Checks that a world can be made of a mesh alone.
   * @throws vimlop::Error when needsCT(): "this model error (...) needs the CT (--ct), not a mesh".
   */
  void requireMeshWorld() const;
  /**
   * @brief Checks the settings.
   * @throws vimlop::Error naming the first problem (a value out of its range).
   */
  void validate() const;
};

/// @brief Distances of the truth surface's vertices to the model surface, mm.
struct SurfaceDistanceSummary
{
  double meanMm = 0.0;
  double medianMm = 0.0;
  double p95Mm = 0.0;
  double maxMm = 0.0;
};

/// @brief A simulated world: the truth the endoscope sees and the model a user has.
struct SimulatedWorld
{
  /// The patient's airway as it is (rendered, and where the path runs), CT frame.
  TriangleMesh truth;
  /// The surface registered to, CT frame (the patient's).
  TriangleMesh model;
  /// The canonical poses a user has, carried from the template through the
  /// warp, CT frame; empty when the template is the patient (the pipeline
  /// then makes them from the model).
  std::vector<CameraPose> canonicalPosesCT;
  /// How far the truth lies from the model.
  SurfaceDistanceSummary truthToModel;
  /// With a deformation: the mean and largest error of the warp at the
  /// template airway's vertices (the registration's map against the known
  /// one), mm, and the registration's time, s.
  double warpErrorMeanMm = 0.0;
  double warpErrorMaxMm = 0.0;
  double warpSeconds = 0.0;
  /// With swelling: its largest displacement (mm) and the swollen area (mm^2).
  double swellingMaxMm = 0.0;
  double swollenAreaMm2 = 0.0;
  /// The registration's warnings and notes on what was made.
  std::vector<std::string> notes;

  /// @brief The world's account for truth/world.json (the options are the caller's).
  nlohmann::json toJson() const;
};

/**
 * @brief The world of `options` around the CT `ct` (its airway is the
 * template's): see SimulatedWorldOptions. Notes go to `progress` as
 * "world: ...". The ideal world's model and truth are both the airway
 * `vimlop segment` makes of `ct`.
 * @throws vimlop::Error for invalid options, a CT without an airway, a
 * failed template registration, or on cancellation.
 */
SimulatedWorld makeSimulatedWorld(
  const CTVolume& ct, const SimulatedWorldOptions& options, const EvaluationProgress& progress);

/**
 * @brief The world of `options` around a given airway mesh (both model and,
 * before swelling, truth).
 * @throws vimlop::Error when the options need the CT (needsCT()): "this model
 * error needs the CT (--ct), not a mesh".
 */
SimulatedWorld makeSimulatedWorld(const TriangleMesh& airway, const SimulatedWorldOptions& options);

/**
 * @brief Writes what a user of the world has, `model.vtp` (the surface to
 * register to) and, when the poses came from the template,
 * `canonical-poses.json` (for `register --init canonical:...`), and the
 * truth apart: `truth/surface.vtp` and `truth/world.json` (toJson()).
 * @throws vimlop::Error if a file cannot be written.
 */
void writeSimulatedWorld(const SimulatedWorld& world, const std::string& folder);

/// @brief Distances of `truth`'s vertices to the surface of `model` (mm).
SurfaceDistanceSummary surfaceDistances(const TriangleMesh& truth, const TriangleMesh& model);

} // namespace vimlop

#endif
