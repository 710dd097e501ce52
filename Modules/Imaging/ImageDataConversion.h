#ifndef vimlop_ImageDataConversion_h
#define vimlop_ImageDataConversion_h

#include <vimlop/Imaging/CTVolume.h>

#include "VIMLOPImagingModule.h"

class vtkImageData;

namespace vimlop
{

/**
 * @brief Copies a volume into `image` as float scalars named "Intensity",
 * keeping origin, spacing and direction (VTK 9.1's image direction matrix).
 */
VIMLOPIMAGING_EXPORT void copyToImageData(const CTVolume& volume, vtkImageData* image);

/**
 * @brief A volume from the first point-data scalars of `image` (any numeric type).
 * @throws vimlop::Error if the image is not 3-D or has no scalars.
 */
VIMLOPIMAGING_EXPORT CTVolume fromImageData(vtkImageData* image);

} // namespace vimlop

#endif
