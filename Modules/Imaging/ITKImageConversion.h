#ifndef vimlop_ITKImageConversion_h
#define vimlop_ITKImageConversion_h

// Private to the Imaging module's ITK translation units (not installed):
// copies between CTVolume and itk::Image. Like every ITK translation unit,
// those that include this header include no Eigen (see CTVolume.h).

#include <vimlop/Imaging/CTVolume.h>

#include <itkImage.h>

#include <algorithm>

namespace vimlop::itkconv
{

/// @brief An ITK image with the grid (size, origin, spacing, direction) of `volume`, uninitialised.
template <typename TImage>
typename TImage::Pointer allocateLike(const CTVolume& volume)
{
  auto image = TImage::New();
  typename TImage::SizeType size;
  typename TImage::SpacingType spacing;
  typename TImage::PointType origin;
  typename TImage::DirectionType direction;
  for (unsigned axis = 0; axis < 3; ++axis)
  {
    size[axis] = static_cast<itk::SizeValueType>(volume.dims[axis]);
    spacing[axis] = volume.spacingMm[axis];
    origin[axis] = volume.originMm[axis];
    for (unsigned row = 0; row < 3; ++row)
    {
      direction(row, axis) = volume.direction[3 * row + axis];
    }
  }
  image->SetRegions(typename TImage::RegionType(size));
  image->SetSpacing(spacing);
  image->SetOrigin(origin);
  image->SetDirection(direction);
  image->Allocate();
  return image;
}

/// @brief An ITK image holding the intensities of `volume` (converted to the pixel type).
template <typename TImage>
typename TImage::Pointer toITKImage(const CTVolume& volume)
{
  typename TImage::Pointer image = allocateLike<TImage>(volume);
  using Pixel = typename TImage::PixelType;
  std::transform(volume.intensities.begin(), volume.intensities.end(), image->GetBufferPointer(),
    [](float v) { return static_cast<Pixel>(v); });
  return image;
}

/// @brief The grid of an ITK image as a CTVolume with no intensities.
template <typename TImage>
CTVolume gridOf(const TImage* image)
{
  CTVolume volume;
  const typename TImage::RegionType region = image->GetLargestPossibleRegion();
  for (unsigned axis = 0; axis < 3; ++axis)
  {
    volume.dims[axis] = static_cast<int>(region.GetSize(axis));
    volume.spacingMm[axis] = image->GetSpacing()[axis];
    volume.originMm[axis] = image->GetOrigin()[axis];
    for (unsigned row = 0; row < 3; ++row)
    {
      volume.direction[3 * row + axis] = image->GetDirection()(row, axis);
    }
  }
  // An image whose region does not start at index 0 (a crop) has its origin
  // moved so that CTVolume's index 0 is the region's first voxel.
  typename TImage::PointType first;
  image->TransformIndexToPhysicalPoint(region.GetIndex(), first);
  for (unsigned axis = 0; axis < 3; ++axis)
  {
    volume.originMm[axis] = first[axis];
  }
  return volume;
}

/// @brief A CTVolume with the grid and the pixels (as float) of an ITK image.
template <typename TImage>
CTVolume fromITKImage(const TImage* image)
{
  CTVolume volume = gridOf(image);
  const auto* buffer = image->GetBufferPointer();
  volume.intensities.resize(volume.numberOfVoxels());
  std::transform(buffer, buffer + volume.numberOfVoxels(), volume.intensities.begin(),
    [](auto v) { return static_cast<float>(v); });
  return volume;
}

} // namespace vimlop::itkconv

#endif
