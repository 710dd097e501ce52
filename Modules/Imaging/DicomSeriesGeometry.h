#ifndef vimlop_DicomSeriesGeometry_h
#define vimlop_DicomSeriesGeometry_h

#include <vimlop/Imaging/CTVolume.h>

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

/// @brief What checkDicomSeriesGeometry() does with a series whose slices
/// are not stacked along their normal (gantry tilt) or not evenly spaced.
enum class IrregularSeries
{
  Refuse,   ///< throw, naming the slices and the figures (the default)
  Resample, ///< accept it and say what is irregular; resampleDicomStack() makes it regular
};

/// @brief A series that passed the checks: its slices in order along the
/// slice normal, where each lies, and the step between them.
struct DicomSeriesLayout
{
  /// Indices into the checked headers, along the slice normal (row x column).
  std::vector<std::size_t> order;
  /// The median step between neighbouring slices, mm.
  double sliceStepMm = 0.0;
  /// Per slice of `order`: its distance from the first along the normal, mm.
  std::vector<double> alongMm;
  /// Per slice of `order`: how far its position lies beside the normal
  /// through the first slice's, along the row and the column direction, mm.
  std::vector<std::array<double, 2>> besideMm;
  /// Empty for a regular series; otherwise (IrregularSeries::Resample) what
  /// is irregular about it, in the words a refusal would have used.
  std::vector<std::string> irregularities;
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
  const DicomSeriesTolerances& tolerances = DicomSeriesTolerances(),
  IrregularSeries irregular = IrregularSeries::Refuse);

/**
 * @brief Resamples the slices of a series onto a regular grid, for a series
 * checkDicomSeriesGeometry() accepted with IrregularSeries::Resample.
 *
 * `stack` holds the slices' pixels as read, in `layout.order` (columns x rows
 * x slices; its geometry is not used) and `first` is the header of the first
 * slice of that order. The volume made has its origin at that slice's
 * position, its axes along the row direction, the column direction and the
 * slice normal, the pixel spacing in plane and `layout.sliceStepMm` between
 * slices, from the first slice to the last. Each voxel is interpolated
 * linearly between the two slices around it along the normal and bilinearly
 * within each, at the point where the voxel lies, so a tilted slice is
 * shifted into place and a gap is bridged; a voxel beside a tilted slice's
 * pixels gets `fillHU` (air).
 */
VIMLOPIMAGING_EXPORT CTVolume resampleDicomStack(const CTVolume& stack,
  const DicomSeriesLayout& layout, const DicomSliceHeader& first, float fillHU = -1024.0f);

} // namespace vimlop

#endif
