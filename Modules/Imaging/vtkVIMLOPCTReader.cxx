#include <vimlop/Imaging/vtkVIMLOPCTReader.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/ImageDataConversion.h>

#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>

vtkStandardNewMacro(vtkVIMLOPCTReader);

vtkVIMLOPCTReader::vtkVIMLOPCTReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkVIMLOPCTReader::~vtkVIMLOPCTReader()
{
  this->SetFileName(nullptr);
  this->SetSeriesUID(nullptr);
}

const char* vtkVIMLOPCTReader::GetWarning(int i) const
{
  return i >= 0 && i < this->GetNumberOfWarnings() ? this->Warnings[i].c_str() : nullptr;
}

bool vtkVIMLOPCTReader::ReadVolume()
{
  this->Volume.reset();
  this->FormatName.clear();
  this->Warnings.clear();
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro("no FileName set");
    return false;
  }
  try
  {
    vimlop::CTReadOptions options;
    options.dicomSeriesUID = this->SeriesUID ? this->SeriesUID : "";
    options.resampleIrregularSeries = this->ResampleIrregularSeries;
    this->Volume =
      std::make_unique<vimlop::CTVolume>(vimlop::readCTVolume(this->FileName, options));
  }
  catch (const vimlop::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  this->FormatName = this->Volume->format;
  this->Warnings = this->Volume->warnings;
  for (const std::string& warning : this->Warnings)
  {
    vtkWarningMacro(<< warning);
  }
  return true;
}

int vtkVIMLOPCTReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (!this->ReadVolume())
  {
    return 0;
  }
  const vimlop::CTVolume& v = *this->Volume;
  vtkInformation* info = outputVector->GetInformationObject(0);
  const int extent[6] = { 0, v.dims[0] - 1, 0, v.dims[1] - 1, 0, v.dims[2] - 1 };
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  info->Set(vtkDataObject::SPACING(), v.spacingMm.data(), 3);
  info->Set(vtkDataObject::ORIGIN(), v.originMm.data(), 3);
  info->Set(vtkDataObject::DIRECTION(), v.direction.data(), 9);
  vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_FLOAT, 1);
  return 1;
}

int vtkVIMLOPCTReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (!this->Volume && !this->ReadVolume())
  {
    return 0;
  }
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vimlop::copyToImageData(*this->Volume, output);
  this->Volume.reset();
  return 1;
}

void vtkVIMLOPCTReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "SeriesUID: " << (this->SeriesUID ? this->SeriesUID : "(largest series)") << "\n";
  os << indent << "ResampleIrregularSeries: " << (this->ResampleIrregularSeries ? "on" : "off")
     << "\n";
  os << indent << "FormatName: " << this->FormatName << "\n";
}
