// ITK translation unit: no Eigen here (see CTVolume.h).
#include <vimlop/Imaging/DisplacementFieldIO.h>

#include <vimlop/Core/FileError.h>
#include <vimlop/Imaging/CTHeaderChecks.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/ITKImageFiles.h>

#include <itkImage.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkVector.h>

#include <cmath>
#include <filesystem>

namespace vimlop
{

namespace
{

using FieldImage = itk::Image<itk::Vector<float, 3>, 3>;

} // namespace

void writeDisplacementField(const DisplacementField& field, const std::string& path)
{
  if (!isWritableCTVolumePath(path))
  {
    throwFileError(
      path, "unsupported field output type (expected .nii, .nii.gz, .nrrd, .nhdr, .mha or .mhd)");
  }
  if (!field.isValid())
  {
    throwFileError(path, "the displacement field to write is empty or inconsistent");
  }
  detail::registerImageIOs();
  auto image = FieldImage::New();
  FieldImage::SizeType size;
  FieldImage::SpacingType spacing;
  FieldImage::PointType origin;
  FieldImage::DirectionType direction;
  for (unsigned axis = 0; axis < 3; ++axis)
  {
    size[axis] = static_cast<itk::SizeValueType>(field.dims[axis]);
    spacing[axis] = field.spacingMm[axis];
    origin[axis] = field.originMm[axis];
    for (unsigned row = 0; row < 3; ++row)
    {
      direction(row, axis) = field.direction[3 * row + axis];
    }
  }
  image->SetRegions(FieldImage::RegionType(size));
  image->SetSpacing(spacing);
  image->SetOrigin(origin);
  image->SetDirection(direction);
  image->Allocate();
  FieldImage::PixelType* buffer = image->GetBufferPointer();
  for (std::size_t i = 0; i < field.numberOfPoints(); ++i)
  {
    for (unsigned a = 0; a < 3; ++a)
    {
      buffer[i][a] = static_cast<float>(field.displacements[3 * i + a]);
    }
  }
  auto writer = itk::ImageFileWriter<FieldImage>::New();
  writer->SetFileName(path);
  writer->SetInput(image);
  writer->SetUseCompression(true);
  try
  {
    writer->Update();
  }
  catch (const itk::ExceptionObject& e)
  {
    throwFileError(path, "cannot write the displacement field (" + detail::itkMessage(e) + ")");
  }
}

DisplacementField readDisplacementField(const std::string& path)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
  {
    throwFileError(path, "no such file");
  }
  const std::string format = detail::imageFormatName(path);
  if (format.empty() || format == "DICOM")
  {
    throwFileError(
      path, "unsupported field type (expected .nii, .nii.gz, .nrrd, .nhdr, .mha or .mhd)");
  }
  detail::registerImageIOs();
  // The CT reader's checks: a field file is as hostile as a CT file.
  itk::ImageIOBase::Pointer io = detail::openImageFile(
    path, format, { "displacement field", 3, "a displacement field has 3 (its x, y and z in mm)" });
  auto reader = itk::ImageFileReader<FieldImage>::New();
  reader->SetFileName(path);
  reader->SetImageIO(io);
  try
  {
    reader->Update();
  }
  catch (const std::exception& e) // ITK also throws std::length_error, std::bad_alloc
  {
    throwFileError(path, "cannot read the displacement field (" + detail::itkMessage(e) + ")");
  }
  const FieldImage* image = reader->GetOutput();
  DisplacementField field;
  for (unsigned axis = 0; axis < 3; ++axis)
  {
    field.dims[axis] = static_cast<int>(image->GetLargestPossibleRegion().GetSize(axis));
    field.spacingMm[axis] = image->GetSpacing()[axis];
    field.originMm[axis] = image->GetOrigin()[axis];
    for (unsigned row = 0; row < 3; ++row)
    {
      field.direction[3 * row + axis] = image->GetDirection()(row, axis);
    }
  }
  detail::checkGridGeometry(path, field.spacingMm, field.originMm, field.direction);
  field.displacements.resize(3 * field.numberOfPoints());
  const FieldImage::PixelType* buffer = image->GetBufferPointer();
  for (std::size_t i = 0; i < field.numberOfPoints(); ++i)
  {
    for (unsigned a = 0; a < 3; ++a)
    {
      if (!std::isfinite(buffer[i][a]))
      {
        // A NaN would move every mesh vertex near it to NaN, far from any anatomy.
        throwFileError(
          path, "grid point " + std::to_string(i) + " holds a displacement that is not finite");
      }
      field.displacements[3 * i + a] = buffer[i][a];
    }
  }
  return field;
}

} // namespace vimlop
