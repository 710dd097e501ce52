#include <vimlop/Video/ColmapModel.h>

#include <vimlop/Core/FileError.h>

namespace vimlop::detail
{

void checkPose(const std::string& path, std::uint64_t imageId, const ColmapModel::Image& image)
{
  if (!image.rotation.coeffs().allFinite() || !image.translation.allFinite() ||
    !(image.rotation.norm() > 1e-12))
  {
    throwFileError(path,
      "image " + std::to_string(imageId) +
        " has a non-finite pose or a zero quaternion (expected QW QX QY QZ of a rotation)");
  }
  for (const Eigen::Vector2d& x : image.points2D)
  {
    if (!x.allFinite())
    {
      throwFileError(path, "image " + std::to_string(imageId) + " has a non-finite 2-D point");
    }
  }
}

void checkPoint(const std::string& path, std::uint64_t pointId, const ColmapModel::Point& point)
{
  if (!point.position.allFinite())
  {
    throwFileError(path, "point " + std::to_string(pointId) + " has a non-finite position");
  }
}

} // namespace vimlop::detail
