#ifndef vimlop_Testing_ColmapBinaryWriting_h
#define vimlop_Testing_ColmapBinaryWriting_h

// Pieces of COLMAP's binary model files, written as COLMAP writes them
// (little-endian, as on every machine the tests run on), for the tests that
// build models in memory.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace vimlop::fixtures
{

/// One value as its bytes.
template <typename T>
void put(std::ostream& f, T value)
{
  f.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// One image record of images.bin: id, world-to-camera pose (the quaternion
/// normalised), camera id, name, and 2-D points with their 3-D point ids.
inline void putImage(std::ostream& f, std::uint32_t id, const Eigen::Quaterniond& q,
  const Eigen::Vector3d& t, std::uint32_t camera, const std::string& name,
  const std::vector<std::pair<Eigen::Vector2d, std::uint64_t>>& points)
{
  put(f, id);
  const Eigen::Quaterniond n = q.normalized();
  for (double v : { n.w(), n.x(), n.y(), n.z(), t.x(), t.y(), t.z() })
  {
    put(f, v);
  }
  put(f, camera);
  f.write(name.c_str(), static_cast<std::streamsize>(name.size() + 1));
  put<std::uint64_t>(f, points.size());
  for (const auto& [xy, point] : points)
  {
    put(f, xy.x());
    put(f, xy.y());
    put(f, point);
  }
}

} // namespace vimlop::fixtures

#endif
