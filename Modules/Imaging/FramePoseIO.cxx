#include <vimlop/Imaging/FramePoseIO.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>

namespace vimlop
{

namespace
{

} // namespace

std::vector<FramePose> readFramePoses(const std::string& path)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
  {
    throwFileError(path, "no such file");
  }
  std::ifstream in(path);
  nlohmann::json document;
  try
  {
    in >> document;
  }
  catch (const nlohmann::json::exception&)
  {
    throwFileError(path, "not a JSON file");
  }
  if (!document.is_object() || !document.contains("poses") || !document["poses"].is_array())
  {
    throwFileError(path,
      "no \"poses\" array (expected {\"poses\": [{\"frame_id\": 0, \"camera_to_ct\": [16 "
      "numbers]}, ...]})");
  }
  std::vector<FramePose> poses;
  int index = 0;
  for (const nlohmann::json& entry : document["poses"])
  {
    const std::string where = "pose " + std::to_string(index);
    if (!entry.is_object() || !entry.contains("frame_id") || !entry["frame_id"].is_number_integer())
    {
      throwFileError(path, where + " has no integer \"frame_id\"");
    }
    const nlohmann::json& matrix =
      entry.contains("camera_to_ct") ? entry["camera_to_ct"] : nlohmann::json();
    if (!matrix.is_array() || matrix.size() != 16 ||
      !std::all_of(
        matrix.begin(), matrix.end(), [](const nlohmann::json& v) { return v.is_number(); }))
    {
      throwFileError(
        path, where + ": \"camera_to_ct\" must be 16 numbers (a 4x4 matrix, row-major)");
    }
    Eigen::Matrix4d m;
    for (int i = 0; i < 16; ++i)
    {
      m(i / 4, i % 4) = matrix[static_cast<std::size_t>(i)].get<double>();
    }
    // Read wide: a 64-bit id read as int wraps, and 2^40 became frame 0.
    const std::int64_t id = entry["frame_id"].get<std::int64_t>();
    if (id < 0 || id > std::numeric_limits<int>::max())
    {
      throwFileError(path,
        where + ": frame_id " + std::to_string(id) + " is out of range (0 to " +
          std::to_string(std::numeric_limits<int>::max()) + ")");
    }
    FramePose pose;
    pose.frameId = static_cast<int>(id);
    try
    {
      pose.cameraToWorld = CameraPose::fromMatrix(m, 1e-5);
    }
    catch (const Error& e)
    {
      throwFileError(path, where + ": " + e.what());
    }
    poses.push_back(pose);
    ++index;
  }
  try
  {
    checkFramePoses(poses);
  }
  catch (const Error& e)
  {
    throwFileError(path, e.what());
  }
  return poses;
}

nlohmann::json framePosesJson(const std::vector<FramePose>& poses)
{
  nlohmann::json document;
  document["frame"] = "CT (LPS, mm); camera x right, y down, z forward";
  document["poses"] = nlohmann::json::array();
  for (const FramePose& pose : poses)
  {
    const Eigen::Matrix4d m = pose.cameraToWorld.matrix();
    std::vector<double> values(16);
    for (int i = 0; i < 16; ++i)
    {
      values[static_cast<std::size_t>(i)] = m(i / 4, i % 4);
    }
    document["poses"].push_back({ { "frame_id", pose.frameId }, { "camera_to_ct", values } });
  }
  return document;
}

void writeFramePoses(const std::vector<FramePose>& poses, const std::string& path)
{
  writeFileAtomically(path, framePosesJson(poses).dump(2) + "\n");
}

} // namespace vimlop
