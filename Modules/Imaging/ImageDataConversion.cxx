#include <vimlop/Imaging/ImageDataConversion.h>

#include <vimlop/Core/Error.h>

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkPointData.h>

namespace vimlop
{

void copyToImageData(const CTVolume& volume, vtkImageData* image)
{
  image->SetDimensions(volume.dims[0], volume.dims[1], volume.dims[2]);
  image->SetSpacing(volume.spacingMm.data());
  image->SetOrigin(volume.originMm.data());
  image->SetDirectionMatrix(volume.direction.data());
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("Intensity");
  scalars->SetNumberOfTuples(static_cast<vtkIdType>(volume.intensities.size()));
  std::copy(volume.intensities.begin(), volume.intensities.end(), scalars->GetPointer(0));
  image->GetPointData()->SetScalars(scalars);
}

CTVolume fromImageData(vtkImageData* image)
{
  if (!image || image->GetDataDimension() != 3)
  {
    throw Error("the image is not a 3-D volume");
  }
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars || scalars->GetNumberOfComponents() != 1)
  {
    throw Error("the image has no single-component scalars");
  }
  CTVolume volume;
  image->GetDimensions(volume.dims.data());
  image->GetSpacing(volume.spacingMm.data());
  image->GetOrigin(volume.originMm.data());
  vtkMatrix3x3* direction = image->GetDirectionMatrix();
  std::copy(direction->GetData(), direction->GetData() + 9, volume.direction.begin());
  volume.intensities.resize(volume.numberOfVoxels());
  for (std::size_t i = 0; i < volume.intensities.size(); ++i)
  {
    volume.intensities[i] = static_cast<float>(scalars->GetTuple1(static_cast<vtkIdType>(i)));
  }
  volume.format = "vtkImageData";
  return volume;
}

} // namespace vimlop
