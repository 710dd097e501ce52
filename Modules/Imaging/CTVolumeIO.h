#ifndef vimlop_CTVolumeIO_h
#define vimlop_CTVolumeIO_h

#include <vimlop/Imaging/CTVolume.h>

#include "VIMLOPImagingModule.h"

#include <string>

namespace vimlop
{

/**
 * @brief Reads a CT volume in the CT frame (ITK physical, LPS).
 *
 * Accepts NIfTI (`.nii`, `.nii.gz`), NRRD (`.nrrd`, `.nhdr`), MetaImage
 * (`.mha`, `.mhd`), a DICOM file (`.dcm`) or a folder holding a DICOM series
 * (slices sorted by position through GDCM), and InVesalius projects (`.inv3`).
 * When a folder holds several series, `dicomSeriesUID` picks one; if it is
 * empty the series with the most slices is read and a warning names it.
 * Intensities come out as float (rescale slope and intercept applied).
 *
 * @throws vimlop::Error with a one-line message naming the file and the
 * problem: missing, unsupported extension, unreadable or truncated, not 3-D.
 */
VIMLOPIMAGING_EXPORT CTVolume readCTVolume(
  const std::string& path, const std::string& dicomSeriesUID = std::string());

/// @brief True when `path` has an extension readCTVolume() accepts, or is a folder.
VIMLOPIMAGING_EXPORT bool isCTVolumePath(const std::string& path);

/// @brief True when `path` has an extension writeCTVolume() accepts.
VIMLOPIMAGING_EXPORT bool isWritableCTVolumePath(const std::string& path);

/**
 * @brief Writes a volume as NIfTI, NRRD or MetaImage, chosen by extension.
 * @throws vimlop::Error if the extension is not one of those or writing fails.
 */
VIMLOPIMAGING_EXPORT void writeCTVolume(const CTVolume& volume, const std::string& path);

} // namespace vimlop

#endif
