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
  MeanSquares
};

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

  /// SyN stage: similarity measure. Default Mattes mutual information.
  TemplateRegistrationMetric metric = TemplateRegistrationMetric::MattesMutualInformation;
  /// SyN stage: voxel size (mm) of each level, coarse to fine. Default 4, 2 mm.
  std::vector<double> synLevelSpacingMm{ 4.0, 2.0 };
  /// SyN stage: iterations per level. Default 20, 10.
  std::vector<int> synIterations{ 20, 10 };
  /// SyN stage: largest update per iteration, in voxels of the level. Default 0.3.
  double synLearningRate = 0.3;
  /// Variance (voxels^2 of the level) of the Gaussian that smooths each
  /// update field. Default 3 (as ANTs' usual SyN[0.1, 3, 0]).
  double updateFieldVariance = 3.0;
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
 * 4. **SyN**: ITK's greedy symmetric diffeomorphic registration
 *    (itk::SyNImageRegistrationMethod), multi-resolution, on the template
 *    crop and the matching patient crop, the affine map composed before it;
 * 5. the composed map is sampled as two displacement fields.
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
  /// Things the user should know (for instance a poor final correlation).
  std::vector<std::string> warnings;

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
