#ifndef vimlop_LinearTransformIO_h
#define vimlop_LinearTransformIO_h

#include "VIMLOPImagingModule.h"

#include <array>
#include <string>

/**
 * @file LinearTransformIO.h
 * @brief One linear transform in an ITK transform file, the form ITK, ANTs
 * and 3D Slicer exchange transforms in.
 *
 * An ITK transform file holds a *resampling* transform: the map from the
 * points of the fixed (output) space to the points of the moving (input)
 * space, both in ITK physical coordinates (LPS, mm for a patient frame).
 * These functions read and write the point map as it is; which way round a
 * transform is stored is the caller's choice, stated where it makes it (see
 * Documentation/Exchange.md for the files VIMLOP writes).
 *
 * The format follows the extension: `.tfm` or `.txt` (ITK's text format),
 * `.h5` or `.hdf5` (ITK's HDF5 format), `.mat` (ITK's MATLAB format, which
 * ANTs writes its affine transforms in).
 *
 * Plain data, no Eigen (see CTVolume.h): a 4 x 4 matrix is 16 numbers in
 * row-major order whose last row is 0 0 0 1.
 */

namespace vimlop
{

/// @brief A 4 x 4 affine point map x -> A x + t, row-major; the last row is 0 0 0 1.
using AffineMatrix4 = std::array<double, 16>;

/// @brief True when `path` ends with an extension of an ITK transform file above.
VIMLOPIMAGING_EXPORT bool isLinearTransformPath(const std::string& path);

/**
 * @brief Writes `pointMap` as ITK's `AffineTransform_double_3_3` (centre 0, so
 * the file's parameters are the 3 x 3 matrix row by row and the translation),
 * any scale and shear included; numbers are written so that they read back
 * exactly.
 * @throws vimlop::Error "'path': ..." for an extension that is not one of an
 * ITK transform file, a matrix whose last row is not 0 0 0 1 or that has a
 * value that is not finite, or a file that cannot be written.
 */
VIMLOPIMAGING_EXPORT void writeLinearTransformFile(
  const AffineMatrix4& pointMap, const std::string& path);

/**
 * @brief Reads the one transform of an ITK transform file as a 4 x 4 point map
 * (its centre and offset folded in). Accepts every linear ITK transform
 * (affine, rigid, similarity, versor, Euler, translation, scale...).
 * @throws vimlop::Error "'path': ..." for a missing or unreadable file, an
 * extension that is not one of an ITK transform file, a file that holds
 * several transforms or a composite one, or a transform that is not linear
 * (a B-spline or a displacement field), naming it.
 */
VIMLOPIMAGING_EXPORT AffineMatrix4 readLinearTransformFile(const std::string& path);

} // namespace vimlop

#endif
