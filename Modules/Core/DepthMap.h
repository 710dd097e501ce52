#ifndef vimlop_DepthMap_h
#define vimlop_DepthMap_h

#include <cstddef>
#include <limits>
#include <vector>

namespace vimlop
{

/**
 * @brief Per-pixel depth of a rendered or simulated view.
 *
 * Depth is the camera z coordinate (mm along the optical axis, not the
 * distance along the ray) of the surface seen through each pixel centre;
 * +infinity where no surface is seen. Rows are stored top to bottom as in
 * OpenCV images: pixel (u, v) is `depthMm[v * widthPx + u]`.
 */
struct DepthMap
{
  int widthPx = 0;
  int heightPx = 0;
  std::vector<float> depthMm;

  static constexpr float noSurface() { return std::numeric_limits<float>::infinity(); }

  float at(int u, int v) const { return this->depthMm[static_cast<size_t>(v) * this->widthPx + u]; }
};

} // namespace vimlop

#endif
