#ifndef vimlop_DisplacementFieldIO_h
#define vimlop_DisplacementFieldIO_h

#include <vimlop/Imaging/DisplacementField.h>

#include "VIMLOPImagingModule.h"

#include <string>

/**
 * @file DisplacementFieldIO.h
 * @brief Displacement fields as 3-component vector images (NIfTI, NRRD,
 * MetaImage), in ITK's convention: each voxel holds the displacement (mm, in
 * the LPS frame of the grid) of its physical point. ITK's
 * DisplacementFieldTransform, ANTs and 3D Slicer read these files.
 */

namespace vimlop
{

/**
 * @brief Writes `field` (stored as float) to `.nii`, `.nii.gz`, `.nrrd`, `.nhdr`, `.mha` or `.mhd`.
 * @throws vimlop::Error for an invalid field, an unsupported extension or a failed write.
 */
VIMLOPIMAGING_EXPORT void writeDisplacementField(
  const DisplacementField& field, const std::string& path);

/**
 * @brief Reads a field written by writeDisplacementField() (or any 3-D image with 3 components).
 * @throws vimlop::Error naming the file and the problem.
 */
VIMLOPIMAGING_EXPORT DisplacementField readDisplacementField(const std::string& path);

} // namespace vimlop

#endif
