#ifndef vimlop_TemplateWarpProtocol_h
#define vimlop_TemplateWarpProtocol_h

#include <vimlop/Evaluation/AnatomyEdits.h>
#include <vimlop/Evaluation/EvaluationProgress.h>
#include <vimlop/Evaluation/PatientScan.h>
#include <vimlop/Imaging/CTVolume.h>
#include <vimlop/Imaging/TemplateRegistration.h>

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief Settings of P4, the template warp (DESIGN section 6).
struct TemplateWarpProtocolOptions
{
  /// Largest displacement of the known deformation over the airway, mm (default 5).
  double maxDisplacementMm = 5.0;
  /// Control point spacing of the known deformation, mm (default 30).
  double controlSpacingMm = 30.0;
  /// Standard deviation of the noise added to the patient, HU (default 20).
  double noiseHU = 20.0;
  /// Seed of the deformation; the noise uses seed + 1000 (default 1).
  unsigned seed = 1;
  /// How the patient is scanned: its grid, blur and the head's position
  /// (default: the template's grid, the head where it was).
  PatientScanOptions scan;
  /// Local edits of the patient's anatomy (default none); placed with `seed`
  /// on the template's airway wall, applied before the deformation. Vertices
  /// and canonical poses near an edit are left out of the errors: the known
  /// map does not hold there.
  AnatomyEditOptions edits;
  /// VIMLOP's registration (default: TemplateRegistration's defaults, which
  /// suit head CTs); its region is set to the bounds of the airway mesh.
  TemplateRegistrationOptions registration;
  /// Run elastix on the same pair when it is installed (default true).
  bool runElastix = true;
  /// Folder with the elastix parameter files affine.txt and bspline.txt
  /// (default: the ones VIMLOP ships, see defaultElastixParametersFolder()).
  std::string elastixParametersFolder;
  /// Folder for elastix's images, logs and results; required when elastix runs.
  std::string elastixWorkFolder;

  /// @throws vimlop::Error naming the first invalid setting.
  void validate() const;
};

/// @brief Per-vertex errors of a warped airway mesh against the known deformation, mm.
struct VertexErrorSummary
{
  double meanMm = 0.0;
  /// 95th percentile (nearest rank).
  double p95Mm = 0.0;
  double maxMm = 0.0;
};

/**
 * @brief Orientation errors of carried poses, with both poses turned by the
 * walls around them instead of the map's Jacobian at the centre: the
 * rotation that best carries (least squares, no scale) the template's wall
 * vertices within 15 mm of the centre, away from every edit, to their
 * images. The walls are what the camera sees and where image edges fix the
 * map; the centre lies in the air, where none does. Poses with fewer than 10
 * such vertices are left out.
 */
struct WallOrientationSummary
{
  std::size_t poses = 0;
  double meanDeg = 0.0;
  double p95Deg = 0.0;
  double maxDeg = 0.0;
};

/// @brief Errors of carried camera poses against the poses the known map carries.
struct PoseErrorSummary
{
  std::size_t poses = 0;
  /// Optical centre, mm.
  double meanMm = 0.0;
  double p95Mm = 0.0;
  double maxMm = 0.0;
  /// Orientation: the angle of the relative rotation, degrees.
  double meanDeg = 0.0;
  double p95Deg = 0.0;
  double maxDeg = 0.0;
  /// Where (template frame, mm) the pose with the largest orientation error
  /// sits, and the distance (mm) from there to the nearest template wall:
  /// a pose far from every wall is turned by a map that no image feature
  /// fixes there.
  std::array<double, 3> maxDegAtMm{ 0.0, 0.0, 0.0 };
  double maxDegWallDistanceMm = 0.0;
  /// The orientation errors with both poses turned by the walls.
  WallOrientationSummary byWalls;
};

/// @brief The result of P4.
struct TemplateWarpProtocolReport
{
  unsigned seed = 0;
  double maxDisplacementMm = 0.0;
  double controlSpacingMm = 0.0;
  double noiseHU = 0.0;
  PatientScanOptions scan;
  AnatomyEditOptions editOptions;
  std::vector<AnatomyEdit> edits;
  /// Voxels the edits changed, and the vertices and poses left out near them.
  std::size_t editedVoxels = 0;
  std::size_t verticesNearEdits = 0;
  std::size_t posesNearEdits = 0;
  /// Vertices of the template's airway mesh, and the airway's volume (cm³).
  std::size_t vertices = 0;
  double airwayVolumeCm3 = 0.0;
  /// VIMLOP's registration (TemplateRegistration): the warped mesh's errors.
  VertexErrorSummary errors;
  /// Where the largest error is (template frame, mm): typically on the cap
  /// that closes the airway where it leaves the CT's field of view, which no
  /// image content guides.
  std::array<double, 3> maxAtMm{ 0.0, 0.0, 0.0 };
  /// Wall-clock time of the registration and the warp of the mesh, s.
  double runtimeS = 0.0;
  /// The template's canonical poses (makeCanonicalPoses() with its
  /// defaults) carried by the registration as `vimlop warp` carries them.
  PoseErrorSummary poseErrors;
  /// How far the known map's own two orientations of each pose lie apart:
  /// turned by the walls against turned by its Jacobian at the centre. A
  /// large deformation turns the walls around a camera by other angles than
  /// the air at its centre, so the true orientation of a carried pose is
  /// only defined to about this.
  WallOrientationSummary truthWallsAgainstJacobian;
  /// The errors with no registration, and with its affine part alone.
  VertexErrorSummary beforeRegistration;
  VertexErrorSummary affineOnly;
  /// The registration's own account.
  double affineS = 0.0;
  double synS = 0.0;
  double bsplineS = 0.0;
  double overlapFraction = 0.0;
  double initialCorrelation = 0.0;
  double affineCorrelation = 0.0;
  double finalCorrelation = 0.0;
  std::array<double, 6> templateCropMm{ 0, 0, 0, 0, 0, 0 };
  /// The registration's settings, its region included.
  TemplateRegistrationOptions settings;
  /// The registration's warnings (e.g. a low correlation).
  std::vector<std::string> warnings;

  /// @brief elastix's figures on the same pair, when it ran.
  struct Elastix
  {
    VertexErrorSummary errors;
    /// The canonical poses carried by elastix's map (its Jacobian from
    /// points 1 mm along each axis).
    PoseErrorSummary poseErrors;
    /// Registration plus transformation, s, and that over VIMLOP's runtime.
    double runtimeS = 0.0;
    double runtimeRatio = 0.0;
    std::vector<std::string> parameterFiles;
  };
  std::optional<Elastix> elastix;
  /// "ran", "not installed" or "not run (--no-elastix)".
  std::string elastixStatus;

  /// @brief The report as written by `vimlop evaluate warp` (less the CT's name).
  nlohmann::json toJson() const;
  /// @brief "seed S, D mm: mean ... (before: mean ...)[; elastix ...]", the
  /// figures `vimlop evaluate warp` prints.
  std::string summaryText() const;
  /**
   * @brief Checks VIMLOP's errors against required bounds (negative: none).
   * @throws vimlop::Error "the mean vertex error X mm exceeds the required Y
   * mm" (or the 95th percentile's) when one is exceeded.
   */
  void requireErrorsAtMost(double meanMm, double p95Mm) const;
  /**
   * @brief Checks that VIMLOP's mean error and runtime are at most elastix's
   * in this run (the bar of Documentation/TemplateWarp.md).
   * @throws vimlop::Error naming the figure that is worse, or elastix's status
   * when it did not run.
   */
  void requireNoWorseThanElastix() const;
};

/**
 * @brief Runs P4 on `templateCT`: segments its airway and meshes it, makes a
 * patient by a known smooth deformation plus noise (SyntheticDeformation),
 * registers the template to the patient (TemplateRegistration) and measures
 * the warped mesh's per-vertex errors against the known deformation; then
 * elastix on the same pair, when asked for and installed. Progress goes to
 * `progress` in thousandths, named after the running step.
 * @throws vimlop::Error for invalid options, a CT without an airway, a
 * failed registration, or cancellation.
 */
TemplateWarpProtocolReport runTemplateWarpProtocol(const CTVolume& templateCT,
  const TemplateWarpProtocolOptions& options, const EvaluationProgress& progress);

} // namespace vimlop

#endif
