#ifndef vimlop_DicomSeriesGeometry_h
#define vimlop_DicomSeriesGeometry_h

#include "VIMLOPImagingModule.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief What one DICOM slice's header says about where its pixels lie.
 *
 * The values are the header's own, parsed but not judged: a missing element
 * is `has... = false`, an unparsable number is NaN. checkDicomSeriesGeometry()
 * judges them. No ITK here, so the checks are tested on headers made in memory.
 */
struct DicomSliceHeader
{
  /// The file's name, for messages.
  std::string file;
  /// Who and what: Series and Study Instance UID (0020,000E), (0020,000D), Patient ID (0010,0020).
  std::string seriesInstanceUID;
  std::string studyInstanceUID;
  std::string patientID;
  /// Image Position (Patient) (0020,0032): the first pixel's centre, mm, LPS.
  std::array<double, 3> positionMm{};
  bool hasPosition = false;
  /// Image Orientation (Patient) (0020,0037): the row direction, then the column direction.
  std::array<double, 6> orientation{};
  bool hasOrientation = false;
  /// Pixel Spacing (0028,0030): between rows, then between columns, mm.
  std::array<double, 2> pixelSpacingMm{};
  bool hasPixelSpacing = false;
  int rows = 0;
  int columns = 0;
  /// Bytes of pixel data the file holds, and the bytes its header promises
  /// (rows x columns x samples x bits allocated / 8); 0 when the pixel data
  /// are compressed, whose length says nothing about completeness.
  std::uint64_t pixelBytes = 0;
  std::uint64_t expectedPixelBytes = 0;
};

/**
 * @brief Reads the geometry elements of one DICOM file with GDCM, and how
 * many bytes of pixel data the file holds. Throws vimlop::Error when the
 * file is not DICOM.
 */
VIMLOPIMAGING_EXPORT DicomSliceHeader readDicomSliceHeader(const std::string& file);

/// @brief The tolerances of checkDicomSeriesGeometry(); the defaults are far
/// below a CT voxel and far above the rounding of DICOM's decimal strings.
struct DicomSeriesTolerances
{
  /// Orientation vectors: |length - 1| and |row . column| at most this.
  double orthonormality = 1e-3;
  /// Largest angle between two slices' orientations, degrees.
  double orientationDeg = 0.1;
  /// Largest in-plane drift of a slice from the stack's axis (the slice
  /// normal through the first slice), as a fraction of the pixel spacing.
  double inPlaneDriftPixels = 0.1;
  /// Largest departure of one step between slices from the series' median
  /// step: this fraction of the median, but at least minimumStepDeviationMm.
  double stepFraction = 0.01;
  double minimumStepDeviationMm = 0.01;
};

/// @brief A series that passed the checks: its slices in order along the
/// slice normal, and the step between them.
struct DicomSeriesLayout
{
  /// Indices into the checked headers, along the slice normal (row x column).
  std::vector<std::size_t> order;
  double sliceStepMm = 0.0;
};

/**
 * @brief The checks a DICOM series passes before VIMLOP makes a volume of it
 * (Documentation/Reliability.md, "CT geometry"): every slice has a position,
 * orthonormal orientation vectors, a finite positive pixel spacing, the same
 * size and complete pixel data; all share one orientation; the positions are
 * distinct and lie on one line along the slice normal (no gantry tilt); the
 * steps between them are even (no missing slice). A volume made from a
 * series that fails one of them would put the airway in the wrong place, so
 * the first failure throws vimlop::Error naming the slices and the figures.
 */
VIMLOPIMAGING_EXPORT DicomSeriesLayout checkDicomSeriesGeometry(
  const std::vector<DicomSliceHeader>& slices,
  const DicomSeriesTolerances& tolerances = DicomSeriesTolerances());

} // namespace vimlop

#endif
