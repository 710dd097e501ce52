#ifndef vimlop_AirwayPhantom_h
#define vimlop_AirwayPhantom_h

// Small synthetic head CTs with known anatomy, built in memory, for the
// segmentation, surface and registration tests. No Eigen here: the
// registration tests include ITK-free code only, but this header is meant to
// be usable from any test.

#include <vimlop/Imaging/CTVolume.h>

#include <array>
#include <cmath>
#include <functional>

namespace vimlop::fixtures
{

constexpr float kAirHU = -1000.0f;
constexpr float kSoftTissueHU = 40.0f;
constexpr float kBoneHU = 900.0f;

/// A volume of `dims` voxels of `spacing` mm, identity direction, origin 0, filled with air.
inline CTVolume emptyVolume(std::array<int, 3> dims, std::array<double, 3> spacing = { 1, 1, 1 })
{
  CTVolume v;
  v.dims = dims;
  v.spacingMm = spacing;
  v.intensities.assign(v.numberOfVoxels(), kAirHU);
  v.format = "phantom";
  return v;
}

/// Sets every voxel whose index (i, j, k) satisfies `inside` to `value`.
inline void paint(CTVolume& v, float value, const std::function<bool(int, int, int)>& inside)
{
  std::size_t n = 0;
  for (int k = 0; k < v.dims[2]; ++k)
  {
    for (int j = 0; j < v.dims[1]; ++j)
    {
      for (int i = 0; i < v.dims[0]; ++i, ++n)
      {
        if (inside(i, j, k))
        {
          v.intensities[n] = value;
        }
      }
    }
  }
}

inline bool inBox(int i, int j, int k, std::array<int, 6> box)
{
  return i >= box[0] && i <= box[1] && j >= box[2] && j <= box[3] && k >= box[4] && k <= box[5];
}

/**
 * @brief A 64 x 64 x 48 head phantom, 1 mm voxels, identity direction.
 *
 * In index coordinates (equal to mm here): an ellipsoidal head of soft tissue
 * with a bone shell, centred at (32, 32, 24); anterior is +j (the phantom's
 * "face"), superior +k. Air spaces inside it:
 * - the airway: the box kAirwayBox, open to the outside through a 4 x 4
 *   "nostril" channel that runs down (-k) out of the bottom of the head;
 * - a sinus: kSinusBox, behind a one-voxel wall of tissue at i = 37;
 * - a small air cell: kCellBox (8 voxels).
 * Outside the head: a head rest (a tissue slab at j = 1..2) joined to the
 * back of the head by a pad, with air between the two that is open at the
 * sides, as on a real scanner table.
 */
struct HeadPhantom
{
  static constexpr std::array<int, 6> kAirwayBox{ 28, 36, 38, 50, 14, 24 };
  static constexpr std::array<int, 6> kNostrilBox{ 30, 33, 44, 47, 0, 13 };
  static constexpr std::array<int, 6> kSinusBox{ 38, 43, 40, 48, 14, 22 };
  static constexpr std::array<int, 6> kCellBox{ 20, 21, 26, 27, 30, 31 };

  static CTVolume make()
  {
    CTVolume v = emptyVolume({ 64, 64, 48 });
    auto ellipsoid = [](int i, int j, int k, double shrink)
    {
      const double x = (i - 32.0) / (24.0 - shrink);
      const double y = (j - 32.0) / (27.0 - shrink);
      const double z = (k - 24.0) / (21.0 - shrink);
      return x * x + y * y + z * z <= 1.0;
    };
    paint(v, kBoneHU, [&](int i, int j, int k) { return ellipsoid(i, j, k, 0.0); });
    paint(v, kSoftTissueHU, [&](int i, int j, int k) { return ellipsoid(i, j, k, 2.0); });
    // Head rest and the pad between it and the back of the head.
    paint(
      v, kSoftTissueHU, [](int, int j, int k) { return j >= 1 && j <= 2 && k >= 4 && k <= 44; });
    paint(v, kSoftTissueHU,
      [](int i, int j, int k)
      { return i >= 29 && i <= 35 && j >= 3 && j <= 8 && k >= 20 && k <= 28; });
    paint(v, kAirHU, [](int i, int j, int k) { return inBox(i, j, k, kAirwayBox); });
    paint(v, kAirHU, [](int i, int j, int k) { return inBox(i, j, k, kNostrilBox); });
    paint(v, kAirHU, [](int i, int j, int k) { return inBox(i, j, k, kSinusBox); });
    paint(v, kAirHU, [](int i, int j, int k) { return inBox(i, j, k, kCellBox); });
    return v;
  }

  /// Voxels of a box.
  static int boxVoxels(std::array<int, 6> b)
  {
    return (b[1] - b[0] + 1) * (b[3] - b[2] + 1) * (b[5] - b[4] + 1);
  }
};

/// A label volume (1 inside a sphere of `radiusMm` about the physical point `centreMm`, 0 outside).
inline CTVolume sphereLabel(std::array<int, 3> dims, std::array<double, 3> spacing,
  std::array<double, 3> origin, std::array<double, 9> direction, std::array<double, 3> centreMm,
  double radiusMm)
{
  CTVolume v = emptyVolume(dims, spacing);
  v.originMm = origin;
  v.direction = direction;
  std::size_t n = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i, ++n)
      {
        const std::array<double, 3> p = v.indexToPhysical({ double(i), double(j), double(k) });
        const double d = std::hypot(p[0] - centreMm[0], p[1] - centreMm[1], p[2] - centreMm[2]);
        v.intensities[n] = d <= radiusMm ? 1.0f : 0.0f;
      }
    }
  }
  return v;
}

} // namespace vimlop::fixtures

#endif
