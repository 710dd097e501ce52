#ifndef vtkVIMLOPCTReader_h
#define vtkVIMLOPCTReader_h

#include "VIMLOPImagingModule.h"

#include <vtkImageAlgorithm.h>

#include <memory>
#include <string>
#include <vector>

namespace vimlop
{
struct CTVolume;
}

/**
 * @brief Reads a CT volume (NIfTI, NRRD, MetaImage, DICOM file or series
 * folder, InVesalius `.inv3`) into a `vtkImageData`.
 *
 * The output keeps the file's origin, spacing and direction (in the CT frame:
 * ITK physical coordinates, LPS, mm) and holds float intensities (HU for CT)
 * named "Intensity". See vimlop::readCTVolume() for the formats and
 * vimlop::readInVesaliusProject() for the orientation assumed for `.inv3`.
 * Read errors go through vtkErrorMacro and fail the update.
 */
class VIMLOPIMAGING_EXPORT vtkVIMLOPCTReader : public vtkImageAlgorithm
{
public:
  static vtkVIMLOPCTReader* New();
  vtkTypeMacro(vtkVIMLOPCTReader, vtkImageAlgorithm)
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// File or DICOM folder to read. Default: none.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// DICOM series to read when the folder holds several. Default: empty, the
  /// series with the most slices.
  vtkSetStringMacro(SeriesUID);
  vtkGetStringMacro(SeriesUID);
  ///@}

  ///@{
  /// Resample a DICOM series tilted by the gantry or unevenly spaced onto a
  /// regular grid (with a warning) instead of failing. Default: off.
  vtkSetMacro(ResampleIrregularSeries, bool);
  vtkGetMacro(ResampleIrregularSeries, bool);
  vtkBooleanMacro(ResampleIrregularSeries, bool);
  ///@}

  /// Format of the last file read, e.g. "NIfTI"; empty before a successful update.
  const char* GetFormatName() const { return this->FormatName.c_str(); }

  /// Warnings of the last read (for instance which DICOM series was chosen).
  int GetNumberOfWarnings() const { return static_cast<int>(this->Warnings.size()); }
  const char* GetWarning(int i) const;

protected:
  vtkVIMLOPCTReader();
  ~vtkVIMLOPCTReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkVIMLOPCTReader(const vtkVIMLOPCTReader&) = delete;
  void operator=(const vtkVIMLOPCTReader&) = delete;

  bool ReadVolume();

  char* FileName = nullptr;
  char* SeriesUID = nullptr;
  bool ResampleIrregularSeries = false;
  std::string FormatName;
  std::vector<std::string> Warnings;
  /// Read in RequestInformation (the header and the voxels come together for
  /// some formats) and released once RequestData has copied it.
  std::unique_ptr<vimlop::CTVolume> Volume;
};

#endif
