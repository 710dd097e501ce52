#ifndef vimlop_EndoscopeImage_h
#define vimlop_EndoscopeImage_h

#include <vimlop/Core/DepthMap.h>

#include <cstdint>
#include <vector>

namespace vimlop
{

/**
 * @brief One frame of the virtual endoscope: the colour picture and the depth
 * of the surface behind every pixel, from the same pinhole camera.
 *
 * `rgb` holds 8-bit red, green, blue per pixel, rows top to bottom (as in
 * OpenCV images, but RGB order): pixel (u, v) starts at `3 * (v * widthPx + u)`.
 * `depth` follows DepthMap's conventions (camera z, mm; +infinity for no surface).
 */
struct EndoscopeImage
{
  int widthPx = 0;
  int heightPx = 0;
  std::vector<std::uint8_t> rgb;
  DepthMap depth;

  /// @brief Channel `c` (0 red, 1 green, 2 blue) of pixel (u, v).
  std::uint8_t channel(int u, int v, int c) const
  {
    return this->rgb[3 * (static_cast<size_t>(v) * this->widthPx + u) + c];
  }
};

} // namespace vimlop

#endif
