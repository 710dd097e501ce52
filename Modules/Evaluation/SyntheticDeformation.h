#ifndef vimlop_SyntheticDeformation_h
#define vimlop_SyntheticDeformation_h

#include <vimlop/Imaging/CTVolume.h>

#include <array>
#include <cstdint>
#include <vector>

namespace vimlop
{

/**
 * @brief Trilinear interpolation of `volume` at a continuous voxel index;
 * -1000 HU (air) outside its grid.
 */
double sampleTrilinear(const CTVolume& volume, const std::array<double, 3>& index);

/**
 * @brief Adds zero-mean Gaussian noise of `noiseHU` standard deviation to
 * every voxel, in voxel order from a Mersenne Twister seeded with `seed`
 * (Box-Muller): the same noise on every platform. Nothing for noiseHU <= 0.
 */
void addGaussianNoise(CTVolume& volume, double noiseHU, std::uint32_t seed);

/// @brief The grid of `volume` (dims, spacing, origin, direction) without its intensities.
CTVolume gridOf(const CTVolume& volume);

/// @brief Parameters of the deformation.
struct SyntheticDeformationOptions
{
  /// Largest displacement over the region. Default 5 mm.
  double maxDisplacementMm = 5.0;
  /// Distance between control points. Default 30 mm.
  double controlSpacingMm = 30.0;
  /// Seed of the random control displacements. Default 1.
  std::uint32_t seed = 1;
  /// Region (CT frame: x min, x max, y min, ...; mm) over which the largest
  /// displacement is measured. Default: an empty box, meaning the whole CT.
  std::array<double, 6> regionMm{ 0.0, -1.0, 0.0, -1.0, 0.0, -1.0 };
};

/**
 * @brief A smooth random deformation of known field, to make a "patient" out
 * of a CT for the template-warp evaluation (DESIGN P4).
 *
 * The field b is a cubic B-spline over the CT's grid: control points every
 * `controlSpacingMm` (rounded to whole voxels along each axis), each with a
 * displacement drawn uniformly from [-1, 1]^3 by a 32-bit Mersenne Twister
 * seeded with `seed` (so a seed gives the same field on every platform), all
 * scaled so that the largest |b| over the voxels of `regionMm` is
 * `maxDisplacementMm`.
 *
 * The patient is the CT resampled through b: P(y) = T(y + b(y)), plus
 * Gaussian noise. So b carries patient points to template points, and a
 * template point x lands in the patient at the y with y + b(y) = x
 * (templateToPatient()), found by fixed-point iteration; it converges because
 * a B-spline with control points tens of mm apart and a few mm of amplitude
 * changes by far less than 1 mm per mm.
 *
 * Frames: the CT frame (LPS mm) for points and displacements.
 */
class SyntheticDeformation
{
public:
  /**
   * @brief The deformation on the grid of `grid` (its dims, spacing, origin, direction).
   * @throws vimlop::Error for a non-3-D grid or options out of range
   * (negative displacement, control spacing under two voxels).
   */
  SyntheticDeformation(const CTVolume& grid, const SyntheticDeformationOptions& options);

  /// @brief b(y): the displacement (mm) that takes patient point y to its template point.
  std::array<double, 3> patientToTemplateDisplacement(
    const std::array<double, 3>& patientPointMm) const;

  /**
   * @brief The patient point y with y + b(y) = `templatePointMm` (to 1e-6 mm).
   * @throws vimlop::Error if the iteration does not converge (a field too strong to invert).
   */
  std::array<double, 3> templateToPatient(const std::array<double, 3>& templatePointMm) const;

  /**
   * @brief The patient CT: `templateCT` (on the grid given at construction)
   * resampled through b with trilinear interpolation (-1000 HU outside),
   * plus zero-mean Gaussian noise of `noiseHU` standard deviation drawn with
   * `noiseSeed`.
   */
  CTVolume makePatient(const CTVolume& templateCT, double noiseHU, std::uint32_t noiseSeed) const;

  /// @brief The largest |b| over the region's voxels (mm): `maxDisplacementMm`.
  double largestDisplacementMm() const { return this->Largest; }

private:
  std::array<double, 3> displacementAtIndex(const std::array<double, 3>& index) const;

  CTVolume Grid; // geometry only
  std::array<int, 3> ControlStepVoxels{ 1, 1, 1 };
  std::array<int, 3> ControlDims{ 0, 0, 0 };
  /// Three values per control point, x fastest.
  std::vector<double> Control;
  double Largest = 0.0;
};

} // namespace vimlop

#endif
