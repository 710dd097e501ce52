#ifndef vimlop_CTSlices_h
#define vimlop_CTSlices_h

// Private to the Report module: the scope in the CT's slices.

#include <vimlop/Core/CameraPose.h>

#include <string>
#include <vector>

namespace vimlop
{

struct CTVolume;

/// @brief Side of one slice's picture, px, and the field it shows, mm.
constexpr int ctSlicePx = 256;
constexpr double ctSliceFieldMm = 120.0;

/**
 * @brief Writes `pngPath`: the axial, coronal and sagittal slices of `ct`
 * through the optical centre of camera `shown` of `camerasCT` (CT frame,
 * LPS, mm), side by side, each a `ctSliceFieldMm` field centred there,
 * `ctSlicePx` pixels square, in a bone window (level 200 HU, width 2000 HU),
 * trilinear, dark blue beyond the scan. Radiological display: axial and coronal with the patient's
 * left on the right, axial anterior up, coronal and sagittal superior up,
 * sagittal anterior on the left; each edge is labelled (R L A P S I). The
 * camera is a yellow ring with an arrow along its view direction (15 mm
 * long in space, drawn as its projection on the slice), and the other
 * cameras' centres, the path, yellow dots.
 * @throws vimlop::Error for an empty volume, no cameras, `shown` out of
 * range, or a file that cannot be written.
 */
void writeCTSlices(const CTVolume& ct, const std::vector<CameraPose>& camerasCT, size_t shown,
  const std::string& pngPath);

} // namespace vimlop

#endif
