#include <vimlop/Video/ColmapTextModel.h>

#include <vimlop/Core/FileError.h>

#include <vimlop/Video/ColmapCameraModel.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

namespace vimlop::detail
{

namespace
{

/// The data lines of a COLMAP text file (comments and blank lines skipped),
/// with their line numbers. images.txt keeps blank lines: an image without
/// 2-D points has an empty second line.
std::vector<std::pair<int, std::string>> dataLines(const std::string& path, bool keepBlank)
{
  std::ifstream in(path);
  if (!in)
  {
    throwFileError(path, "no such file or not readable");
  }
  std::vector<std::pair<int, std::string>> lines;
  std::string line;
  int number = 0;
  while (std::getline(in, line))
  {
    ++number;
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    if (!line.empty() && line[0] == '#')
    {
      continue;
    }
    const bool blank = line.find_first_not_of(" \t") == std::string::npos;
    if (blank && !keepBlank)
    {
      continue;
    }
    lines.emplace_back(number, line);
  }
  return lines;
}

template <typename T>
T parseField(std::istringstream& in, const std::string& path, int line, const char* what)
{
  T value;
  if (!(in >> value))
  {
    throwFileError(path, "line " + std::to_string(line) + ": expected " + what);
  }
  return value;
}

} // namespace

void readCamerasText(const std::string& path, ColmapModel& model)
{
  for (const auto& [line, text] : dataLines(path, false))
  {
    std::istringstream in(text);
    const auto id = parseField<std::uint32_t>(in, path, line, "a camera id");
    const auto name = parseField<std::string>(in, path, line, "a camera model");
    const ColmapCameraModel& info = modelByName(path, name);
    const auto width = parseField<std::int64_t>(in, path, line, "the image width");
    const auto height = parseField<std::int64_t>(in, path, line, "the image height");
    std::vector<double> p(static_cast<size_t>(info.parameters));
    for (double& v : p)
    {
      v = parseField<double>(in, path, line, "a camera parameter");
    }
    model.cameras[id].intrinsics = intrinsicsOf(path, id, info, p, width, height);
  }
}

void readImagesText(const std::string& path, ColmapModel& model)
{
  const std::vector<std::pair<int, std::string>> lines = dataLines(path, true);
  size_t i = 0;
  while (i < lines.size())
  {
    const auto& [line, text] = lines[i];
    if (text.find_first_not_of(" \t") == std::string::npos)
    {
      ++i; // a stray blank line between images
      continue;
    }
    std::istringstream in(text);
    const auto id = parseField<std::uint32_t>(in, path, line, "an image id");
    ColmapModel::Image image;
    const double qw = parseField<double>(in, path, line, "QW");
    const double qx = parseField<double>(in, path, line, "QX");
    const double qy = parseField<double>(in, path, line, "QY");
    const double qz = parseField<double>(in, path, line, "QZ");
    image.rotation = Eigen::Quaterniond(qw, qx, qy, qz);
    for (int a = 0; a < 3; ++a)
    {
      image.translation[a] = parseField<double>(in, path, line, "a translation");
    }
    image.cameraId = parseField<std::uint32_t>(in, path, line, "a camera id");
    std::getline(in >> std::ws, image.name);
    if (image.name.empty())
    {
      throwFileError(path, "line " + std::to_string(line) + ": expected an image name");
    }
    ++i;
    if (i < lines.size())
    {
      std::istringstream points(lines[i].second);
      double x = 0.0;
      double y = 0.0;
      long long point3D = 0;
      while (points >> x >> y >> point3D)
      {
        image.points2D.emplace_back(x, y);
      }
      ++i;
    }
    checkPose(path, id, image);
    model.images[id] = std::move(image);
  }
}

void readPointsText(const std::string& path, ColmapModel& model)
{
  for (const auto& [line, text] : dataLines(path, false))
  {
    std::istringstream in(text);
    const auto id = parseField<std::uint64_t>(in, path, line, "a point id");
    ColmapModel::Point point;
    for (int a = 0; a < 3; ++a)
    {
      point.position[a] = parseField<double>(in, path, line, "a coordinate");
    }
    for (int a = 0; a < 3; ++a)
    {
      point.colour[a] = parseField<int>(in, path, line, "a colour");
    }
    parseField<double>(in, path, line, "the error");
    std::uint32_t image = 0;
    std::uint32_t index = 0;
    while (in >> image >> index)
    {
      point.track.emplace_back(image, index);
    }
    checkPoint(path, id, point);
    model.points[id] = std::move(point);
  }
}

} // namespace vimlop::detail
