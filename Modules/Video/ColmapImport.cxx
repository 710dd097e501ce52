#include <vimlop/Video/ColmapImport.h>

#include <vimlop/Core/Error.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace vimlop
{

namespace
{

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw Error("'" + path + "': " + problem);
}

struct ColmapCamera
{
  PinholeCamera intrinsics;
};

struct ColmapImage
{
  std::string name;
  std::uint32_t cameraId = 0;
  Eigen::Quaterniond rotation; ///< world to camera
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector2d> points2D;
};

struct ColmapPoint
{
  Eigen::Vector3d position;
  Eigen::Vector3i colour;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> track; ///< (image id, point2D index)
};

struct ColmapModel
{
  std::map<std::uint32_t, ColmapCamera> cameras;
  std::map<std::uint32_t, ColmapImage> images;
  std::map<std::uint64_t, ColmapPoint> points;
};

/// Name, parameter count and COLMAP id of the camera models VIMLOP reads.
struct ModelInfo
{
  const char* name;
  int id;
  int parameters;
};
constexpr ModelInfo supportedModels[] = { { "SIMPLE_PINHOLE", 0, 3 }, { "PINHOLE", 1, 4 },
  { "SIMPLE_RADIAL", 2, 4 }, { "RADIAL", 3, 5 }, { "OPENCV", 4, 8 } };
/// Every COLMAP model by id, for messages about the ones VIMLOP does not read.
constexpr const char* colmapModelNames[] = { "SIMPLE_PINHOLE", "PINHOLE", "SIMPLE_RADIAL", "RADIAL",
  "OPENCV", "OPENCV_FISHEYE", "FULL_OPENCV", "FOV", "SIMPLE_RADIAL_FISHEYE", "RADIAL_FISHEYE",
  "THIN_PRISM_FISHEYE" };

std::string supportedList()
{
  std::string list;
  for (const ModelInfo& m : supportedModels)
  {
    list += (list.empty() ? "" : ", ") + std::string(m.name);
  }
  return list;
}

const ModelInfo& modelByName(const std::string& path, const std::string& name)
{
  for (const ModelInfo& m : supportedModels)
  {
    if (name == m.name)
    {
      return m;
    }
  }
  const bool known = std::find(std::begin(colmapModelNames), std::end(colmapModelNames), name) !=
    std::end(colmapModelNames);
  fail(path,
    (known ? "unsupported camera model '" : "unknown camera model '") + name +
      "' (supported: " + supportedList() + ")");
}

const ModelInfo& modelById(const std::string& path, int id)
{
  for (const ModelInfo& m : supportedModels)
  {
    if (id == m.id)
    {
      return m;
    }
  }
  if (id >= 0 && id < static_cast<int>(std::size(colmapModelNames)))
  {
    fail(path,
      "unsupported camera model '" + std::string(colmapModelNames[id]) +
        "' (supported: " + supportedList() + ")");
  }
  fail(path,
    "unknown camera model id " + std::to_string(id) + " (supported: " + supportedList() + ")");
}

/// Images larger than this on a side are not endoscope frames; such sizes
/// come from corrupt files (and would overflow pixel counts downstream).
constexpr std::int64_t maxImageSidePx = 1 << 16;

/// COLMAP parameters to VIMLOP intrinsics: pixel centres move from 0.5 to 0.
/// Refuses sizes and parameters that no camera has (NaN, zero focal length).
PinholeCamera intrinsicsOf(const std::string& path, std::uint64_t cameraId, const ModelInfo& model,
  const std::vector<double>& p, std::int64_t width, std::int64_t height)
{
  const std::string camera = "camera " + std::to_string(cameraId);
  if (width < 1 || height < 1 || width > maxImageSidePx || height > maxImageSidePx)
  {
    fail(path,
      camera + " has an image size of " + std::to_string(width) + " x " + std::to_string(height) +
        " px (expected 1 to " + std::to_string(maxImageSidePx) + " per side)");
  }
  for (const double v : p)
  {
    if (!std::isfinite(v))
    {
      fail(path, camera + " has a non-finite parameter");
    }
  }
  if (!(p[0] > 0.0) || ((model.id == 1 || model.id == 4) && !(p[1] > 0.0)))
  {
    fail(path, camera + " has a focal length that is not positive");
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
    default:
      break;
  }
  return k;
}

// ---------------------------------------------------------------- text files

/// A world-to-camera pose must be finite with a non-zero quaternion (it is
/// normalised on use); a point position must be finite.
void checkPose(const std::string& path, std::uint64_t imageId, const ColmapImage& image)
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

void checkPoint(const std::string& path, std::uint64_t pointId, const ColmapPoint& point)
{
  if (!point.position.allFinite())
  {
    fail(path, "point " + std::to_string(pointId) + " has a non-finite position");
  }
}

/// The data lines of a COLMAP text file (comments and blank lines skipped),
/// with their line numbers. images.txt keeps blank lines: an image without
/// 2-D points has an empty second line.
std::vector<std::pair<int, std::string>> dataLines(const std::string& path, bool keepBlank)
{
  std::ifstream in(path);
  if (!in)
  {
    fail(path, "no such file or not readable");
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
    fail(path, "line " + std::to_string(line) + ": expected " + what);
  }
  return value;
}

void readCamerasText(const std::string& path, ColmapModel& model)
{
  for (const auto& [line, text] : dataLines(path, false))
  {
    std::istringstream in(text);
    const auto id = parseField<std::uint32_t>(in, path, line, "a camera id");
    const auto name = parseField<std::string>(in, path, line, "a camera model");
    const ModelInfo& info = modelByName(path, name);
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
    ColmapImage image;
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
      fail(path, "line " + std::to_string(line) + ": expected an image name");
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
    ColmapPoint point;
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

// -------------------------------------------------------------- binary files

class BinaryReader
{
public:
  explicit BinaryReader(const std::string& path)
    : Path(path)
    , In(path, std::ios::binary)
  {
    if (!this->In)
    {
      fail(path, "no such file or not readable");
    }
  }

  template <typename T>
  T read()
  {
    // COLMAP writes little-endian, as the x86 and ARM machines VIMLOP runs on are.
    T value;
    if (!this->In.read(reinterpret_cast<char*>(&value), sizeof(T)))
    {
      fail(this->Path, "the file is truncated");
    }
    return value;
  }

  std::string readString()
  {
    std::string s;
    char c = 0;
    while (true)
    {
      if (!this->In.get(c))
      {
        fail(this->Path, "the file is truncated");
      }
      if (c == '\0')
      {
        return s;
      }
      s.push_back(c);
    }
  }

  /// A count read from the file, checked against what the rest of the file can hold.
  std::uint64_t readCount(std::uint64_t bytesPerItem)
  {
    const auto count = this->read<std::uint64_t>();
    const std::streampos here = this->In.tellg();
    this->In.seekg(0, std::ios::end);
    const std::streamoff remaining = this->In.tellg() - here;
    this->In.seekg(here);
    if (bytesPerItem > 0 && count > static_cast<std::uint64_t>(remaining) / bytesPerItem)
    {
      fail(this->Path,
        "the file is truncated or not a COLMAP model (count " + std::to_string(count) + ")");
    }
    return count;
  }

private:
  std::string Path;
  std::ifstream In;
};

void readCamerasBinary(const std::string& path, ColmapModel& model)
{
  BinaryReader in(path);
  const std::uint64_t count = in.readCount(24);
  for (std::uint64_t c = 0; c < count; ++c)
  {
    const auto id = in.read<std::uint32_t>();
    const auto modelId = in.read<std::int32_t>();
    const ModelInfo& info = modelById(path, modelId);
    const auto width = in.read<std::uint64_t>();
    const auto height = in.read<std::uint64_t>();
    std::vector<double> p(static_cast<size_t>(info.parameters));
    for (double& v : p)
    {
      v = in.read<double>();
    }
    // Sizes beyond int64 are as absurd as negative ones; clamp for the check.
    const auto side = [](std::uint64_t v)
    { return static_cast<std::int64_t>(std::min<std::uint64_t>(v, maxImageSidePx + 1)); };
    model.cameras[id].intrinsics = intrinsicsOf(path, id, info, p, side(width), side(height));
  }
}

void readImagesBinary(const std::string& path, ColmapModel& model)
{
  BinaryReader in(path);
  const std::uint64_t count = in.readCount(68);
  for (std::uint64_t i = 0; i < count; ++i)
  {
    const auto id = in.read<std::uint32_t>();
    ColmapImage image;
    double q[4];
    for (double& v : q)
    {
      v = in.read<double>();
    }
    image.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    for (int a = 0; a < 3; ++a)
    {
      image.translation[a] = in.read<double>();
    }
    image.cameraId = in.read<std::uint32_t>();
    image.name = in.readString();
    const std::uint64_t points = in.readCount(24);
    image.points2D.reserve(points);
    for (std::uint64_t p = 0; p < points; ++p)
    {
      const double x = in.read<double>();
      const double y = in.read<double>();
      in.read<std::uint64_t>(); // the 3-D point id; the tracks in points3D say the same
      image.points2D.emplace_back(x, y);
    }
    checkPose(path, id, image);
    model.images[id] = std::move(image);
  }
}

void readPointsBinary(const std::string& path, ColmapModel& model)
{
  BinaryReader in(path);
  const std::uint64_t count = in.readCount(43);
  for (std::uint64_t i = 0; i < count; ++i)
  {
    const auto id = in.read<std::uint64_t>();
    ColmapPoint point;
    for (int a = 0; a < 3; ++a)
    {
      point.position[a] = in.read<double>();
    }
    for (int a = 0; a < 3; ++a)
    {
      point.colour[a] = in.read<std::uint8_t>();
    }
    in.read<double>(); // error
    const std::uint64_t length = in.readCount(8);
    for (std::uint64_t t = 0; t < length; ++t)
    {
      const auto image = in.read<std::uint32_t>();
      const auto index = in.read<std::uint32_t>();
      point.track.emplace_back(image, index);
    }
    checkPoint(path, id, point);
    model.points[id] = std::move(point);
  }
}

/// "frame2" before "frame10".
bool naturalLess(const std::string& a, const std::string& b)
{
  size_t i = 0;
  size_t j = 0;
  while (i < a.size() && j < b.size())
  {
    const bool da = std::isdigit(static_cast<unsigned char>(a[i])) != 0;
    const bool db = std::isdigit(static_cast<unsigned char>(b[j])) != 0;
    if (da && db)
    {
      size_t ie = i;
      size_t je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie])))
      {
        ++ie;
      }
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je])))
      {
        ++je;
      }
      const std::string na = a.substr(i, ie - i);
      const std::string nb = b.substr(j, je - j);
      const std::string sa = na.substr(std::min(na.find_first_not_of('0'), na.size()));
      const std::string sb = nb.substr(std::min(nb.find_first_not_of('0'), nb.size()));
      if (sa.size() != sb.size())
      {
        return sa.size() < sb.size();
      }
      if (sa != sb)
      {
        return sa < sb;
      }
      i = ie;
      j = je;
    }
    else
    {
      if (a[i] != b[j])
      {
        return a[i] < b[j];
      }
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

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
    fail(folder, "no such folder (expected a COLMAP sparse model folder such as sparse/0)");
  }
  if (format == ColmapFormat::Automatic)
  {
    const bool binary = fs::exists(fs::path(folder) / "cameras.bin", ec);
    const bool text = fs::exists(fs::path(folder) / "cameras.txt", ec);
    if (!binary && !text)
    {
      fail(folder, "not a COLMAP sparse model (no cameras.bin or cameras.txt)");
    }
    format = binary ? ColmapFormat::Binary : ColmapFormat::Text;
  }
  const bool binary = format == ColmapFormat::Binary;
  const std::string ext = binary ? ".bin" : ".txt";
  const std::string camerasPath = (fs::path(folder) / ("cameras" + ext)).string();
  const std::string imagesPath = (fs::path(folder) / ("images" + ext)).string();
  const std::string pointsPath = (fs::path(folder) / ("points3D" + ext)).string();
  ColmapModel model;
  if (binary)
  {
    readCamerasBinary(camerasPath, model);
    readImagesBinary(imagesPath, model);
    readPointsBinary(pointsPath, model);
  }
  else
  {
    readCamerasText(camerasPath, model);
    readImagesText(imagesPath, model);
    readPointsText(pointsPath, model);
  }
  if (model.images.empty())
  {
    fail(imagesPath, "the model has no registered images");
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
      fail(imagesPath,
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
        fail(pointsPath,
          "point " + std::to_string(id) + " is observed by image " + std::to_string(imageId) +
            ", which " + fs::path(imagesPath).filename().string() + " does not hold (dangling id)");
      }
      if (index >= image->second.points2D.size())
      {
        fail(pointsPath,
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
