#ifndef vimlop_CTVolumeIO_h
#define vimlop_CTVolumeIO_h

#include <vimlop/Imaging/CTVolume.h>

#include "VIMLOPImagingModule.h"

#include <string>

namespace vimlop
{

/// @brief How readCTVolume() reads a DICOM folder.
struct CTReadOptions
{
  /// The series to read when a folder holds several; empty: the one with the most slices.
  std::string dicomSeriesUID;
  /**
   * A series tilted by the gantry or unevenly spaced (missing slices) is
   * refused by default. True: it is resampled onto a regular grid along the
   * slice normal (resampleDicomStack()), with a warning that says what was
   * irregular, and the volume's identity records it ("resampled").
   */
  bool resampleIrregularSeries = false;
};

/**
 * @brief Reads a CT volume in the CT frame (ITK physical, LPS).
 *
 * Accepts NIfTI (`.nii`, `.nii.gz`), NRRD (`.nrrd`, `.nhdr`), MetaImage
 * (`.mha`, `.mhd`), a DICOM file (`.dcm`) or a folder holding a DICOM series
 * (slices sorted by position through GDCM), and InVesalius projects (`.inv3`).
 * When a folder holds several series, `options.dicomSeriesUID` picks one;
 * if it is empty the series with the most slices is read and a warning names
 * it. A DICOM series passes checkDicomSeriesGeometry() first.
 * Intensities come out as float (rescale slope and intercept applied).
 *
 * @throws vimlop::Error with a one-line message naming the file and the
 * problem: missing, unsupported extension, unreadable or truncated, not 3-D.
 */
VIMLOPIMAGING_EXPORT CTVolume readCTVolume(
  const std::string& path, const CTReadOptions& options = CTReadOptions());

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
