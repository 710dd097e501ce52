#include <vimlop/Video/ColmapModel.h>

#include <vimlop/Core/Error.h>

namespace vimlop::detail
{

[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw Error("'" + path + "': " + problem);
}

void checkPose(const std::string& path, std::uint64_t imageId, const ColmapModel::Image& image)
{
  if (!image.rotation.coeffs().allFinite() || !image.translation.allFinite() ||
    !(image.rotation.norm() > 1e-12))
  {
    fail(path,
      "image " + std::to_string(imageId) +
        " has a non-finite pose or a zero quaternion (expected QW QX QY QZ of a rotation)");
  }
  for (const Eigen::Vector2d& x : image.points2D)
  {
    if (!x.allFinite())
    {
      fail(path, "image " + std::to_string(imageId) + " has a non-finite 2-D point");
    }
  }
}

void checkPoint(const std::string& path, std::uint64_t pointId, const ColmapModel::Point& point)
{
  if (!point.position.allFinite())
  {
    fail(path, "point " + std::to_string(pointId) + " has a non-finite position");
  }
}

} // namespace vimlop::detail
