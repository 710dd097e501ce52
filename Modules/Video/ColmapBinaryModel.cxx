#include <vimlop/Video/ColmapBinaryModel.h>

#include <vimlop/Core/FileError.h>

#include <vimlop/Video/ColmapCameraModel.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <vector>

namespace vimlop::detail
{

namespace
{

class BinaryReader
{
public:
  explicit BinaryReader(const std::string& path)
    : Path(path)
    , In(path, std::ios::binary)
  {
    if (!this->In)
    {
      throwFileError(path, "no such file or not readable");
    }
  }

  template <typename T>
  T read()
  {
    // COLMAP writes little-endian, as the x86 and ARM machines VIMLOP runs on are.
    T value;
    if (!this->In.read(reinterpret_cast<char*>(&value), sizeof(T)))
    {
      throwFileError(this->Path, "the file is truncated");
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
        throwFileError(this->Path, "the file is truncated");
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
      throwFileError(this->Path,
        "the file is truncated or not a COLMAP model (count " + std::to_string(count) + ")");
    }
    return count;
  }

private:
  std::string Path;
  std::ifstream In;
};

} // namespace

void readCamerasBinary(const std::string& path, ColmapModel& model)
{
  BinaryReader in(path);
  const std::uint64_t count = in.readCount(24);
  for (std::uint64_t c = 0; c < count; ++c)
  {
    const auto id = in.read<std::uint32_t>();
    const auto modelId = in.read<std::int32_t>();
    const ColmapCameraModel& info = modelById(path, modelId);
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
    ColmapModel::Image image;
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
    ColmapModel::Point point;
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

} // namespace vimlop::detail
