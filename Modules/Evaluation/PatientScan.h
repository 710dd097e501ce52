#ifndef vimlop_PatientScan_h
#define vimlop_PatientScan_h

#include <vimlop/Imaging/CTVolume.h>

#include <array>
#include <cstdint>

namespace vimlop
{

/// @brief How P4's synthetic patient is scanned: its grid, its reconstruction, the head's position.
struct PatientScanOptions
{
  /// In-plane voxel spacing (mm; the grid's first two axes). Default 0: the template's.
  double pixelSpacingMm = 0.0;
  /// Slice spacing, which is also the slice thickness (mm; the grid's third
  /// axis). Default 0: the template's.
  double sliceSpacingMm = 0.0;
  /// Extra Gaussian blur of a softer reconstruction kernel (sigma, mm). Default 0.
  double blurMm = 0.0;
  /// The head turned in the scanner about the left-right axis through the
  /// template grid's centre (a nod, deg). Default 0. In [-30, 30].
  double rotationDeg = 0.0;
  /// And moved (mm, CT frame). Default none. Each in [-50, 50].
  std::array<double, 3> shiftMm{ 0.0, 0.0, 0.0 };

  /// @brief True when the scan is the template's grid and the head does not move.
  bool isTemplateGrid() const;
  /**
   * @brief Checks the ranges.
   * @throws vimlop::Error naming the first value out of range.
   */
  void validate() const;
};

/**
 * @brief The scan of a deformed head (P4's harder pairs, issue 18): the head
 * moved rigidly in the scanner (M: rotation about the template grid's centre,
 * then the shift), the field of view kept where the template's was, the
 * slices and pixels resampled, the image blurred as a slice profile and a
 * softer kernel would, and the noise added last.
 *
 * Frames: the CT frame (LPS mm). A point x of the deformed head lies at
 * place(x) in the scanned patient.
 */
class PatientScan
{
public:
  /**
   * @brief The scan of heads on the grid of `templateGrid`.
   * @throws vimlop::Error for options out of range.
   */
  PatientScan(const CTVolume& templateGrid, const PatientScanOptions& options);

  /// @brief M(x): a point of the deformed head (mm) to the scanned patient.
  std::array<double, 3> place(const std::array<double, 3>& pointMm) const;

  /**
   * @brief The scanned patient. `deformed` (on the template's grid) is
   * blurred with a Gaussian whose sigma per axis is sqrt(blur^2 + (s_new^2 -
   * s_old^2) / 2.355^2), the new voxel's profile (a full width at half
   * maximum of its spacing) less the old one's, then sampled trilinearly at
   * M^-1(y) for each voxel y of the new grid (same origin, direction and
   * extent; -1000 HU outside), then given noise (addGaussianNoise).
   */
  CTVolume scan(CTVolume deformed, double noiseHU, std::uint32_t noiseSeed) const;

private:
  CTVolume Grid; // geometry only
  PatientScanOptions Options;
  std::array<double, 3> CentreMm{};
  /// Rows of M's rotation.
  std::array<std::array<double, 3>, 3> Rotation{};
};

} // namespace vimlop

#endif
