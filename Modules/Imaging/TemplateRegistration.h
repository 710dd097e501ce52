#ifndef vimlop_TemplateRegistration_h
#define vimlop_TemplateRegistration_h

#include <vimlop/Imaging/CTVolume.h>
#include <vimlop/Imaging/DisplacementField.h>
#include <vimlop/Imaging/ProgressCallback.h>

#include "VIMLOPImagingModule.h"

#include <array>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief The similarity measure of the SyN stage.
enum class TemplateRegistrationMetric
{
  /// Mattes mutual information: intensities need not match (different
  /// scanners, contrast). The default.
  MattesMutualInformation,
  /// Mean squared difference: faster; for CTs whose HU agree.
  MeanSquares,
  /// ANTs' neighbourhood cross-correlation (the metric of ANTs' usual SyN):
  /// local, so it tolerates slowly varying intensity differences; slower.
  NeighborhoodCorrelation
};

/// @brief The metric's name on the command line and in JSON: "mi", "ms" or "cc".
VIMLOPIMAGING_EXPORT std::string templateRegistrationMetricName(TemplateRegistrationMetric metric);
/// @brief The metric named `name` ("mi", "ms" or "cc").
/// @throws vimlop::Error "unknown SyN metric 'x' (mi, ms or cc)" for any other name.
VIMLOPIMAGING_EXPORT TemplateRegistrationMetric templateRegistrationMetricFromName(
  const std::string& name);

/// @brief Parameters of TemplateRegistration::compute().
struct TemplateRegistrationOptions
{
  /// The box to register, in the template's CT frame: x min, x max, y min,
  /// y max, z min, z max (mm), e.g. the bounds of the template meshes and
  /// poses. Required (a box with min > max on any axis is refused).
  std::array<double, 6> regionMm{ 0.0, -1.0, 0.0, -1.0, 0.0, -1.0 };
  /// Added around `regionMm` on every side. Default 15 mm.
  double marginMm = 15.0;

  /// Affine stage: voxel size (mm) of each resolution level, coarse to
  /// fine, reached by integer shrinking per axis. Default 4, 2 mm.
  std::vector<double> affineLevelSpacingMm{ 4.0, 2.0 };
  /// Affine stage: iterations per level. Default 100, 50.
  std::vector<int> affineIterations{ 100, 50 };
  /// Histogram bins of Mattes mutual information. Default 32.
  int histogramBins = 32;
  /// Fraction of the crop's voxels sampled by the affine stage (regular
  /// sampling). Default 0.3.
  double affineSamplingFraction = 0.3;

  /// B-spline stage (between the affine stage and SyN): spacing (mm) of the
  /// cubic B-spline's control points at each level, coarse to fine; empty:
  /// no B-spline stage. Default 40, 20, 10 mm, as the elastix peer's
  /// parameter file (P4, Documentation/TemplateWarp.md).
  std::vector<double> bsplineGridMm{ 40.0, 20.0, 10.0 };
  /// B-spline stage: voxel size (mm) of each level: the images are smoothed
  /// with a Gaussian of half that sigma. Default 4, 2, 1 mm.
  std::vector<double> bsplineLevelSpacingMm{ 4.0, 2.0, 1.0 };
  /// B-spline stage: L-BFGS function evaluations per level, at most.
  /// Default 30, 30, 30 (with the bending weight, 100 per level ended at the
  /// same P4 error, 1.4 times slower).
  std::vector<int> bsplineIterations{ 30, 30, 30 };
  /// B-spline stage: samples per level, as a fraction of the voxels the
  /// level's voxel size would give the template crop (random positions,
  /// fixed seed). Default 0.2 (P4 mean 0.19 mm with 0.05, 0.11 mm with 0.2,
  /// without bending energy).
  double bsplineSamplingFraction = 0.2;
  /// B-spline stage: weight (mm^2) of the bending energy (mean squared
  /// Hessian of the displacement, 1/mm^2) added to the negated mutual
  /// information. Default 10 mm^2: without it, more iterations fit the
  /// noise (P4 mean 0.11 mm at 30 evaluations per level, 0.14 at 50); with
  /// 3, 10, 30 or 100 the error no longer depends on the iterations, and 10
  /// is the weakest that beat elastix on P4 seeds 1-3.
  double bsplineBendingWeightMm2 = 10.0;

  /// SyN stage: similarity measure. Default Mattes mutual information.
  TemplateRegistrationMetric metric = TemplateRegistrationMetric::MattesMutualInformation;
  /// SyN stage with NeighborhoodCorrelation: radius of the neighbourhood,
  /// in voxels of the level (a cube of 2r + 1 voxels a side). Default 2.
  int correlationRadiusVoxels = 2;
  /// SyN stage: voxel size (mm) of each level, coarse to fine. Default 8, 4,
  /// 2 mm: the 8 mm level takes the large smooth part of a template-to-patient
  /// deformation cheaply (P4, Documentation/TemplateWarp.md).
  std::vector<double> synLevelSpacingMm{ 8.0, 4.0, 2.0 };
  /// SyN stage: iterations per level, at most (a level stops earlier once
  /// its metric settles). Default 0, 0, 0: after the B-spline stage, SyN
  /// made P4 worse (Documentation/TemplateWarp.md); SyN alone was best with
  /// 60, 40, 15.
  std::vector<int> synIterations{ 0, 0, 0 };
  /// SyN stage: largest update per iteration, in voxels of the level.
  /// Default 0.25: smaller steps ended closer to the truth on P4 (0.1 closer
  /// still, at 3 times the runtime).
  double synLearningRate = 0.25;
  /// Variance (voxels^2 of the level) of the Gaussian that smooths each
  /// update field. Default 6 (ANTs' usual SyN[0.1, 3, 0] has 3; on P4 a
  /// smoother update moved the airway more like the smooth truth).
  double updateFieldVariance = 6.0;
  /// Variance (voxels^2 of the level) of the Gaussian that smooths the total
  /// field after each update. Default 0: none.
  double totalFieldVariance = 0.0;

  /// Least fraction of the template crop that must map into the patient CT
  /// after the affine stage. Default 0.5.
  double minimumOverlap = 0.5;
  /// A final correlation below this adds a warning. Default 0.5.
  double warningCorrelation = 0.5;
};

/**
 * @brief Deformable registration of a template CT to a patient CT (the
 * paper's template-to-patient step, done there with ANTs SyN), restricted to
 * a region of the template (the nasal region) with a margin.
 *
 * Made by TemplateRegistration::compute(), with ITK:
 * 1. both CTs are clamped to [-1000, 2000] HU; the template is cropped to
 *    `regionMm` plus `marginMm`;
 * 2. **affine**: the translation that aligns the centroids of the two heads
 *    (voxels above -500 HU) starts a multi-resolution affine registration of
 *    the template crop to the patient, Mattes mutual information, regular
 *    step gradient descent with physical-shift parameter scales;
 * 3. **overlap check**: the fraction of the template crop that the affine
 *    map sends into the patient volume; below `minimumOverlap` the images do
 *    not overlap and compute() fails;
 * 4. **B-spline** (unless `bsplineGridMm` is empty): a cubic B-spline
 *    deformation after the affine map, its control grid refined level by
 *    level, L-BFGS on Mattes mutual information plus bending energy
 *    (BSplineMutualInformationCost), sampled at 1 mm as a displacement field
 *    with a numerical inverse;
 * 5. **SyN** (refines nothing with the default zero iterations): ITK's
 *    greedy symmetric diffeomorphic registration
 *    (itk::SyNImageRegistrationMethod), multi-resolution, on the template
 *    crop and the matching patient crop, the maps before it composed first;
 * 6. the composed map is sampled as two displacement fields.
 *
 * ITK's registration methods return a transform from the fixed image's
 * points to the moving image's points. The template is the fixed image and
 * the patient the moving one, so the result carries template points to the
 * corresponding patient points: the direction in which template meshes and
 * poses travel. The inverse (patient to template) comes from SyN's inverse
 * field and the inverted affine map.
 *
 * Frames: the template's and the patient's CT frames (LPS mm).
 */
struct TemplateRegistration
{
  /// Template to patient: a template point x goes to x + u(x) in the patient's
  /// frame. Sampled on the template crop's grid (its voxels).
  DisplacementField templateToPatient;
  /// Patient to template, on the grid of the patient crop.
  DisplacementField patientToTemplate;
  /// The affine stage alone, template to patient: y = A x + t, stored as the
  /// rows of [A | t] (3 x 4, row-major, mm).
  std::array<double, 12> affine{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 };
  /// The template crop, template frame: x min, x max, y min, ... (mm).
  std::array<double, 6> templateCropMm{ 0, 0, 0, 0, 0, 0 };
  /// Fraction of the template crop that the affine map sends into the patient volume.
  double overlapFraction = 0.0;
  /// Correlation of the template crop's intensities with the patient's at
  /// the mapped points: before registration (centroids aligned), after the
  /// affine stage and at the end. 1 is a perfect match.
  double initialCorrelation = 0.0;
  double affineCorrelation = 0.0;
  double finalCorrelation = 0.0;
  /// Last value of the metric of each stage (ITK's sign: lower is better).
  double affineMetricValue = 0.0;
  double synMetricValue = 0.0;
  /// Wall-clock time of each stage (s).
  double affineSeconds = 0.0;
  double synSeconds = 0.0;
  /// Wall-clock time of the B-spline stage (s; 0 without it).
  double bsplineSeconds = 0.0;
  /// Things the user should know (for instance a poor final correlation).
  std::vector<std::string> warnings;
  /// The options it ran with, its region included.
  TemplateRegistrationOptions settings;

  /**
   * @brief Registers `templateCT` (fixed) to `patientCT` (moving).
   * @throws vimlop::Error with a one-line message when a volume is not 3-D,
   * the region is empty or outside the template, the options are out of
   * range, or the two CTs do not overlap after the affine stage.
   */
  VIMLOPIMAGING_EXPORT static TemplateRegistration compute(const CTVolume& templateCT,
    const CTVolume& patientCT, const TemplateRegistrationOptions& options,
    const ProgressCallback& progress = ProgressCallback());
};

} // namespace vimlop

#endif
