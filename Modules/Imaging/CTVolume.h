#ifndef vimlop_CTVolume_h
#define vimlop_CTVolume_h

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief A CT volume in memory, in ITK's physical (LPS) frame.
 *
 * Voxel (i, j, k) is stored at `intensities[i + dims[0] * (j + dims[1] * k)]`
 * and lies at the physical point `origin + direction * diag(spacing) * (i, j, k)`
 * in mm, with the direction matrix's columns the index axes in LPS
 * (x to the patient's left, y posterior, z superior). Intensities are
 * Hounsfield units for CT.
 *
 * This struct deliberately uses no Eigen: the ITK 5.2 of Debian carries its
 * own older copy of Eigen under the same include guards, so translation units
 * that include ITK must not include ours (see CTVolumeIO.cxx).
 */
struct CTVolume
{
  std::array<int, 3> dims{ 0, 0, 0 };
  std::array<double, 3> spacingMm{ 1.0, 1.0, 1.0 };
  std::array<double, 3> originMm{ 0.0, 0.0, 0.0 };
  /// Row-major 3x3: element (row, col) is `direction[3 * row + col]`.
  std::array<double, 9> direction{ 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0 };
  std::vector<float> intensities;
  /// Human-readable name of the file format, e.g. "NIfTI" or "InVesalius project".
  std::string format;
  /// Things the user should know about how the file was read (one line each).
  std::vector<std::string> warnings;
  /// Who and what the scan is, when the file says: for DICOM
  /// "series_instance_uid", "study_instance_uid" and "patient_id".
  std::map<std::string, std::string> identity;

  std::size_t numberOfVoxels() const
  {
    return static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  }

  /// @brief Physical point (mm, LPS) of a continuous index.
  std::array<double, 3> indexToPhysical(const std::array<double, 3>& index) const
  {
    std::array<double, 3> p = originMm;
    for (int row = 0; row < 3; ++row)
    {
      for (int col = 0; col < 3; ++col)
      {
        p[row] += direction[3 * row + col] * spacingMm[col] * index[col];
      }
    }
    return p;
  }

  /// @brief Continuous index of a physical point (mm, LPS); the inverse of
  /// indexToPhysical() for an orthonormal direction.
  std::array<double, 3> physicalToIndex(const std::array<double, 3>& pointMm) const
  {
    std::array<double, 3> index{};
    for (int col = 0; col < 3; ++col)
    {
      double projection = 0.0;
      for (int row = 0; row < 3; ++row)
      {
        projection += direction[3 * row + col] * (pointMm[row] - originMm[row]);
      }
      index[col] = projection / spacingMm[col];
    }
    return index;
  }
};

} // namespace vimlop

#endif
