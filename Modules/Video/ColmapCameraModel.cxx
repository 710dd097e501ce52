#include <vimlop/Video/ColmapCameraModel.h>

#include <vimlop/Core/FileError.h>

#include <vimlop/Video/ColmapModel.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace vimlop::detail
{

namespace
{

constexpr ColmapCameraModel supportedModels[] = { { "SIMPLE_PINHOLE", 0, 3 }, { "PINHOLE", 1, 4 },
  { "SIMPLE_RADIAL", 2, 4 }, { "RADIAL", 3, 5 }, { "OPENCV", 4, 8 }, { "OPENCV_FISHEYE", 5, 8 },
  { "FULL_OPENCV", 6, 12 } };
/// Every COLMAP model by id, for messages about the ones VIMLOP does not read.
constexpr const char* colmapModelNames[] = { "SIMPLE_PINHOLE", "PINHOLE", "SIMPLE_RADIAL", "RADIAL",
  "OPENCV", "OPENCV_FISHEYE", "FULL_OPENCV", "FOV", "SIMPLE_RADIAL_FISHEYE", "RADIAL_FISHEYE",
  "THIN_PRISM_FISHEYE" };

std::string supportedList()
{
  std::string list;
  for (const ColmapCameraModel& m : supportedModels)
  {
    list += (list.empty() ? "" : ", ") + std::string(m.name);
  }
  return list;
}

} // namespace

const ColmapCameraModel& modelByName(const std::string& path, const std::string& name)
{
  for (const ColmapCameraModel& m : supportedModels)
  {
    if (name == m.name)
    {
      return m;
    }
  }
  const bool known = std::find(std::begin(colmapModelNames), std::end(colmapModelNames), name) !=
    std::end(colmapModelNames);
  throwFileError(path,
    (known ? "unsupported camera model '" : "unknown camera model '") + name +
      "' (supported: " + supportedList() + ")");
}

const ColmapCameraModel& modelById(const std::string& path, int id)
{
  for (const ColmapCameraModel& m : supportedModels)
  {
    if (id == m.id)
    {
      return m;
    }
  }
  if (id >= 0 && id < static_cast<int>(std::size(colmapModelNames)))
  {
    throwFileError(path,
      "unsupported camera model '" + std::string(colmapModelNames[id]) +
        "' (supported: " + supportedList() + ")");
  }
  throwFileError(path,
    "unknown camera model id " + std::to_string(id) + " (supported: " + supportedList() + ")");
}

PinholeCamera intrinsicsOf(const std::string& path, std::uint64_t cameraId,
  const ColmapCameraModel& model, const std::vector<double>& p, std::int64_t width,
  std::int64_t height)
{
  const std::string camera = "camera " + std::to_string(cameraId);
  if (width < 1 || height < 1 || width > maxImageSidePx || height > maxImageSidePx)
  {
    throwFileError(path,
      camera + " has an image size of " + std::to_string(width) + " x " + std::to_string(height) +
        " px (expected 1 to " + std::to_string(maxImageSidePx) + " per side)");
  }
  for (const double v : p)
  {
    if (!std::isfinite(v))
    {
      throwFileError(path, camera + " has a non-finite parameter");
    }
  }
  if (!(p[0] > 0.0) ||
    ((model.id == 1 || model.id == 4 || model.id == 5 || model.id == 6) && !(p[1] > 0.0)))
  {
    throwFileError(path, camera + " has a focal length that is not positive");
  }
  PinholeCamera k;
  k.widthPx = static_cast<int>(width);
  k.heightPx = static_cast<int>(height);
  const bool single = model.id == 0 || model.id == 2 || model.id == 3;
  k.fx = p[0];
  k.fy = single ? p[0] : p[1];
  k.cx = (single ? p[1] : p[2]) - 0.5;
  k.cy = (single ? p[2] : p[3]) - 0.5;
  switch (model.id)
  {
    case 2: // SIMPLE_RADIAL: f, cx, cy, k
      k.distortion = Eigen::Vector4d(p[3], 0.0, 0.0, 0.0);
      break;
    case 3: // RADIAL: f, cx, cy, k1, k2
      k.distortion = Eigen::Vector4d(p[3], p[4], 0.0, 0.0);
      break;
    case 4: // OPENCV: fx, fy, cx, cy, k1, k2, p1, p2
      k.distortion = Eigen::Vector4d(p[4], p[5], p[6], p[7]);
      break;
    case 5: // OPENCV_FISHEYE: fx, fy, cx, cy, k1, k2, k3, k4 (OpenCV's cv::fisheye)
      k.distortion = Eigen::Vector4d(p[4], p[5], p[6], p[7]);
      k.lensModel = LensModel::Fisheye;
      break;
    case 6: // FULL_OPENCV: fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6 (OpenCV's rational model)
      k.distortion.resize(8);
      for (int i = 0; i < 8; ++i)
      {
        k.distortion[i] = p[static_cast<size_t>(4 + i)];
      }
      break;
    default:
      break;
  }
  return k;
}

} // namespace vimlop::detail
