// ITK translation unit: no Eigen here (see CTVolume.h).
#include <vimlop/Imaging/DisplacementFieldIO.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/ITKImageIOFactories.h>

#include <itkImage.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkVector.h>

#include <filesystem>

namespace vimlop
{

namespace
{

using FieldImage = itk::Image<itk::Vector<float, 3>, 3>;

[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw Error("'" + path + "': " + problem);
}

std::string firstLine(const itk::ExceptionObject& e)
{
  std::string text = e.GetDescription();
  const auto newline = text.find('\n');
  return newline == std::string::npos ? text : text.substr(0, newline);
}

} // namespace

void writeDisplacementField(const DisplacementField& field, const std::string& path)
{
  if (!isWritableCTVolumePath(path))
  {
    fail(
      path, "unsupported field output type (expected .nii, .nii.gz, .nrrd, .nhdr, .mha or .mhd)");
  }
  if (!field.isValid())
  {
    fail(path, "the displacement field to write is empty or inconsistent");
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
    fail(path, "cannot write the displacement field (" + firstLine(e) + ")");
  }
}

DisplacementField readDisplacementField(const std::string& path)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
  {
    fail(path, "no such file");
  }
  detail::registerImageIOs();
  auto reader = itk::ImageFileReader<FieldImage>::New();
  reader->SetFileName(path);
  try
  {
    reader->UpdateOutputInformation();
    if (reader->GetImageIO()->GetNumberOfComponents() != 3 ||
      reader->GetImageIO()->GetNumberOfDimensions() < 3)
    {
      fail(path, "not a 3-D displacement field with 3 components per voxel");
    }
    reader->Update();
  }
  catch (const itk::ExceptionObject& e)
  {
    fail(path, "cannot read the displacement field (" + firstLine(e) + ")");
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
  field.displacements.resize(3 * field.numberOfPoints());
  const FieldImage::PixelType* buffer = image->GetBufferPointer();
  for (std::size_t i = 0; i < field.numberOfPoints(); ++i)
  {
    for (unsigned a = 0; a < 3; ++a)
    {
      field.displacements[3 * i + a] = buffer[i][a];
    }
  }
  return field;
}

} // namespace vimlop
