#ifndef vimlop_VolumeCrop_h
#define vimlop_VolumeCrop_h

#include <vimlop/Imaging/CTVolume.h>

#include "VIMLOPImagingModule.h"

#include <array>
#include <limits>

/**
 * @file VolumeCrop.h
 * @brief Sub-volumes of a CT by physical box, for working on a region (the
 * nasal region) rather than the whole head.
 */

namespace vimlop
{

/**
 * @brief The voxels of `volume` whose box covers `boxMm` (CT frame: x min,
 * x max, y min, y max, z min, z max; mm), clamped to the volume, as a volume
 * of their own on the same grid (same spacing and direction, origin moved),
 * intensities clamped to [`lowest`, `highest`].
 * @throws vimlop::Error if the box misses the volume.
 */
VIMLOPIMAGING_EXPORT CTVolume cropVolume(const CTVolume& volume, const std::array<double, 6>& boxMm,
  float lowest = std::numeric_limits<float>::lowest(),
  float highest = std::numeric_limits<float>::max());

/// @brief Bounds of the voxel centres of `volume` in the CT frame: x min, x max, y min, ... (mm).
VIMLOPIMAGING_EXPORT std::array<double, 6> volumeBounds(const CTVolume& volume);

} // namespace vimlop

#endif
