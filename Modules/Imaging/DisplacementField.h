#ifndef vimlop_DisplacementField_h
#define vimlop_DisplacementField_h

#include "VIMLOPImagingModule.h"

#include <array>
#include <cstddef>
#include <vector>

namespace vimlop
{

/**
 * @brief A dense map between two CT frames, sampled on a grid: the point x
 * (mm) goes to x + u(x), with u trilinearly interpolated between grid points.
 *
 * The grid is laid out like a CTVolume: grid point (i, j, k) lies at
 * `origin + direction * diag(spacing) * (i, j, k)` in the frame the map
 * starts from, and its displacement (mm, in the same axes) is stored at
 * `displacements[3 * (i + dims[0] * (j + dims[1] * k)) + axis]`. This is
 * ITK's (and ANTs') displacement field convention, so fields written by
 * writeDisplacementField() work with ITK's DisplacementFieldTransform.
 *
 * Outside the grid the displacement of the nearest grid point on the border
 * is used (the field is extended by its border values); contains() tells
 * whether a point is inside. Plain data, no Eigen (see CTVolume.h).
 */
struct DisplacementField
{
  std::array<int, 3> dims{ 0, 0, 0 };
  std::array<double, 3> spacingMm{ 1.0, 1.0, 1.0 };
  std::array<double, 3> originMm{ 0.0, 0.0, 0.0 };
  /// Row-major 3x3 with orthonormal columns: the grid axes in the frame.
  std::array<double, 9> direction{ 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0 };
  /// Three values (x, y, z displacement in mm) per grid point, x fastest.
  std::vector<double> displacements;

  std::size_t numberOfPoints() const
  {
    return static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  }

  /// @brief True when the grid is non-empty and `displacements` has 3 values per point.
  VIMLOPIMAGING_EXPORT bool isValid() const;

  /// @brief Physical point (mm) of a continuous grid index.
  VIMLOPIMAGING_EXPORT std::array<double, 3> indexToPhysical(
    const std::array<double, 3>& index) const;

  /// @brief Continuous grid index of a physical point (mm).
  VIMLOPIMAGING_EXPORT std::array<double, 3> physicalToIndex(
    const std::array<double, 3>& pointMm) const;

  /// @brief True when `pointMm` lies within the grid (between its first and last points).
  VIMLOPIMAGING_EXPORT bool contains(const std::array<double, 3>& pointMm) const;

  /// @brief u(x): the trilinearly interpolated displacement at `pointMm` (mm).
  VIMLOPIMAGING_EXPORT std::array<double, 3> displacementAt(
    const std::array<double, 3>& pointMm) const;

  /// @brief x + u(x): where the map sends `pointMm`.
  VIMLOPIMAGING_EXPORT std::array<double, 3> transformPoint(
    const std::array<double, 3>& pointMm) const;
};

} // namespace vimlop

#endif
