#include <vimlop/Video/ColmapImport.h>

#include <vimlop/Core/FileError.h>

#include <vimlop/Video/ColmapBinaryModel.h>
#include <vimlop/Video/ColmapModel.h>
#include <vimlop/Video/ColmapTextModel.h>

#include "FrameFiles.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>

namespace vimlop
{

namespace
{

namespace fs = std::filesystem;

using detail::naturalLess;

} // namespace

std::string colmapPinholeParameters(const PinholeCamera& k)
{
  char text[200];
  std::snprintf(text, sizeof(text), "%.10g,%.10g,%.10g,%.10g", k.fx, k.fy, k.cx + 0.5, k.cy + 0.5);
  return text;
}

SfmReconstruction readColmapModel(const std::string& folder, ColmapFormat format,
  const std::vector<std::string>& frameNames, double sigmaPx, std::vector<std::string>* warnings)
{
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
  {
    throwFileError(
      folder, "no such folder (expected a COLMAP sparse model folder such as sparse/0)");
  }
  if (format == ColmapFormat::Automatic)
  {
    const bool binary = fs::exists(fs::path(folder) / "cameras.bin", ec);
    const bool text = fs::exists(fs::path(folder) / "cameras.txt", ec);
    if (!binary && !text)
    {
      throwFileError(folder, "not a COLMAP sparse model (no cameras.bin or cameras.txt)");
    }
    format = binary ? ColmapFormat::Binary : ColmapFormat::Text;
  }
  const bool binary = format == ColmapFormat::Binary;
  const std::string ext = binary ? ".bin" : ".txt";
  const std::string camerasPath = (fs::path(folder) / ("cameras" + ext)).string();
  const std::string imagesPath = (fs::path(folder) / ("images" + ext)).string();
  const std::string pointsPath = (fs::path(folder) / ("points3D" + ext)).string();
  detail::ColmapModel model;
  if (binary)
  {
    detail::readCamerasBinary(camerasPath, model);
    detail::readImagesBinary(imagesPath, model);
    detail::readPointsBinary(pointsPath, model);
  }
  else
  {
    detail::readCamerasText(camerasPath, model);
    detail::readImagesText(imagesPath, model);
    detail::readPointsText(pointsPath, model);
  }
  if (model.images.empty())
  {
    throwFileError(imagesPath, "the model has no registered images");
  }

  // Frames: in the given order, or the images sorted by name.
  SfmReconstruction r;
  r.source = "colmap";
  std::vector<std::string> names = frameNames;
  if (names.empty())
  {
    for (const auto& [id, image] : model.images)
    {
      names.push_back(image.name);
    }
    std::sort(names.begin(), names.end(), naturalLess);
  }
  std::map<std::string, int> frameOfName;
  for (size_t f = 0; f < names.size(); ++f)
  {
    frameOfName[names[f]] = static_cast<int>(f);
    SfmReconstruction::Frame frame;
    frame.name = names[f];
    r.frames.push_back(frame);
  }
  std::map<std::uint32_t, int> frameOfImage;
  std::vector<std::string> notInFrames;
  for (const auto& [id, image] : model.images)
  {
    const auto camera = model.cameras.find(image.cameraId);
    if (camera == model.cameras.end())
    {
      throwFileError(imagesPath,
        "image '" + image.name + "' uses camera " + std::to_string(image.cameraId) + ", which " +
          fs::path(camerasPath).filename().string() + " does not define");
    }
    const auto frame = frameOfName.find(image.name);
    if (frame == frameOfName.end())
    {
      notInFrames.push_back(image.name);
      continue;
    }
    SfmReconstruction::Frame& f = r.frames[static_cast<size_t>(frame->second)];
    f.registered = true;
    f.intrinsics = camera->second.intrinsics;
    // x_camera = R x_world + t, so the centre is -R^T t and the camera axes are the rows of R.
    const Eigen::Matrix3d rotation = image.rotation.normalized().toRotationMatrix();
    f.cameraToSfm.rotation = rotation.transpose();
    f.cameraToSfm.centre = -rotation.transpose() * image.translation;
    frameOfImage[id] = frame->second;
  }
  if (!notInFrames.empty() && warnings)
  {
    warnings->push_back("COLMAP model: dropped " + std::to_string(notInFrames.size()) +
      " image(s) not among the frames (first: '" + notInFrames.front() + "')");
  }
  for (const SfmReconstruction::Frame& f : r.frames)
  {
    if (!f.registered && warnings)
    {
      warnings->push_back("COLMAP model: frame '" + f.name + "' is not registered");
    }
  }

  int droppedObservations = 0;
  for (const auto& [id, point] : model.points)
  {
    SfmReconstruction::Point p;
    p.position = point.position;
    p.colour = point.colour;
    for (const auto& [imageId, index] : point.track)
    {
      const auto image = model.images.find(imageId);
      if (image == model.images.end())
      {
        throwFileError(pointsPath,
          "point " + std::to_string(id) + " is observed by image " + std::to_string(imageId) +
            ", which " + fs::path(imagesPath).filename().string() + " does not hold (dangling id)");
      }
      if (index >= image->second.points2D.size())
      {
        throwFileError(pointsPath,
          "point " + std::to_string(id) + " refers to 2-D point " + std::to_string(index) +
            " of image '" + image->second.name + "', which has only " +
            std::to_string(image->second.points2D.size()) + " (dangling id)");
      }
      const auto frame = frameOfImage.find(imageId);
      if (frame == frameOfImage.end())
      {
        ++droppedObservations;
        continue;
      }
      p.observations.push_back(
        { frame->second, image->second.points2D[index] - Eigen::Vector2d(0.5, 0.5) });
    }
    if (p.observations.size() >= 2)
    {
      r.points.push_back(std::move(p));
    }
  }
  if (droppedObservations > 0 && warnings)
  {
    warnings->push_back("COLMAP model: dropped " + std::to_string(droppedObservations) +
      " observation(s) in images not among the frames");
  }
  r.computeCovariances(sigmaPx);
  return r;
}

} // namespace vimlop
