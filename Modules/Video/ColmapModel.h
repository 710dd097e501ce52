#ifndef vimlop_ColmapModel_h
#define vimlop_ColmapModel_h

// Private to the Video module (not installed): readColmapModel's view of a
// COLMAP sparse model, as its text and binary readers fill it.

#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/StableLayout.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace vimlop::detail
{

/// The cameras, images and points of a COLMAP sparse model, by COLMAP id.
struct ColmapModel
{
  struct Camera
  {
    PinholeCamera intrinsics;
  };

  struct Image
  {
    std::string name;
    std::uint32_t cameraId = 0;
    QuaterniondUnaligned rotation; ///< world to camera
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector2d> points2D;
  };

  struct Point
  {
    Eigen::Vector3d position;
    Eigen::Vector3i colour;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> track; ///< (image id, point2D index)
  };

  std::map<std::uint32_t, Camera> cameras;
  std::map<std::uint32_t, Image> images;
  std::map<std::uint64_t, Point> points;
};

/// A world-to-camera pose must be finite with a non-zero quaternion (it is
/// normalised on use); a point position must be finite.
void checkPose(const std::string& path, std::uint64_t imageId, const ColmapModel::Image& image);
void checkPoint(const std::string& path, std::uint64_t pointId, const ColmapModel::Point& point);

} // namespace vimlop::detail

#endif
