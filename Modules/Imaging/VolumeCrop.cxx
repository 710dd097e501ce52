#include <vimlop/Imaging/VolumeCrop.h>

#include <vimlop/Core/Error.h>

#include <algorithm>
#include <cmath>

namespace vimlop
{

CTVolume cropVolume(
  const CTVolume& v, const std::array<double, 6>& boxMm, float lowest, float highest)
{
  std::array<double, 3> lo{ 1e300, 1e300, 1e300 };
  std::array<double, 3> hi{ -1e300, -1e300, -1e300 };
  for (int corner = 0; corner < 8; ++corner)
  {
    const std::array<double, 3> p{ boxMm[(corner & 1) ? 1 : 0], boxMm[(corner & 2) ? 3 : 2],
      boxMm[(corner & 4) ? 5 : 4] };
    // index = diag(1 / spacing) D^T (p - origin): the direction is orthonormal.
    for (int col = 0; col < 3; ++col)
    {
      double projection = 0.0;
      for (int row = 0; row < 3; ++row)
      {
        projection += v.direction[3 * row + col] * (p[row] - v.originMm[row]);
      }
      lo[col] = std::min(lo[col], projection / v.spacingMm[col]);
      hi[col] = std::max(hi[col], projection / v.spacingMm[col]);
    }
  }
  std::array<int, 3> first{};
  std::array<int, 3> last{};
  CTVolume out;
  for (int a = 0; a < 3; ++a)
  {
    first[a] = std::max(0, static_cast<int>(std::floor(lo[a])));
    last[a] = std::min(v.dims[a] - 1, static_cast<int>(std::ceil(hi[a])));
    if (last[a] < first[a])
    {
      throw Error("the box to crop lies outside the volume");
    }
    out.dims[a] = last[a] - first[a] + 1;
  }
  out.spacingMm = v.spacingMm;
  out.direction = v.direction;
  out.originMm = v.indexToPhysical({ double(first[0]), double(first[1]), double(first[2]) });
  out.format = v.format;
  out.intensities.resize(out.numberOfVoxels());
  std::size_t n = 0;
  for (int k = first[2]; k <= last[2]; ++k)
  {
    for (int j = first[1]; j <= last[1]; ++j)
    {
      const std::size_t row =
        static_cast<std::size_t>(v.dims[0]) * (j + static_cast<std::size_t>(v.dims[1]) * k);
      for (int i = first[0]; i <= last[0]; ++i)
      {
        out.intensities[n++] = std::clamp(v.intensities[row + i], lowest, highest);
      }
    }
  }
  return out;
}

std::array<double, 6> volumeBounds(const CTVolume& v)
{
  std::array<double, 6> b{ 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (int corner = 0; corner < 8; ++corner)
  {
    const std::array<double, 3> p = v.indexToPhysical({ (corner & 1) ? v.dims[0] - 1.0 : 0.0,
      (corner & 2) ? v.dims[1] - 1.0 : 0.0, (corner & 4) ? v.dims[2] - 1.0 : 0.0 });
    for (int a = 0; a < 3; ++a)
    {
      b[2 * a] = std::min(b[2 * a], p[a]);
      b[2 * a + 1] = std::max(b[2 * a + 1], p[a]);
    }
  }
  return b;
}

} // namespace vimlop
