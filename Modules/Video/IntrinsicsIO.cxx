#include <vimlop/Video/IntrinsicsIO.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>

#include <opencv2/core.hpp>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace vimlop
{

namespace
{

double readNumber(const cv::FileNode& root, const char* key, const std::string& path)
{
  const cv::FileNode node = root[key];
  if (node.empty() || (!node.isReal() && !node.isInt()))
  {
    throwFileError(path, std::string("missing or non-numeric entry '") + key + "'");
  }
  return static_cast<double>(node);
}

/// Checks an OpenCV matrix node's declared size before OpenCV allocates it
/// (a file can declare billions of rows).
void checkMatrixNode(
  const cv::FileNode& node, const char* key, int maxRows, int maxCols, const std::string& path)
{
  if (!node.isMap() || node["rows"].empty() || node["cols"].empty() || !node["rows"].isInt() ||
    !node["cols"].isInt())
  {
    throwFileError(
      path, std::string("'") + key + "' is not an OpenCV matrix (rows, cols, dt, data)");
  }
  const int rows = static_cast<int>(node["rows"]);
  const int cols = static_cast<int>(node["cols"]);
  if (rows < 1 || cols < 1 || rows > maxRows || cols > maxCols)
  {
    throwFileError(path,
      std::string("'") + key + "' has an invalid size " + std::to_string(rows) + "x" +
        std::to_string(cols));
  }
}

/// The lens model that the optional entry `distortion_model` names. Without
/// it, OpenCV's default model, so that every file from before the entry
/// reads as it did. The names are OpenCV's and ROS camera_info's.
LensModel readLensModel(const cv::FileNode& root, const std::string& path)
{
  const cv::FileNode node = root["distortion_model"];
  if (node.empty())
  {
    return LensModel::RadialTangential;
  }
  const std::string name = node.isString() ? static_cast<std::string>(node) : std::string();
  if (name == "plumb_bob" || name == "radial_tangential")
  {
    return LensModel::RadialTangential;
  }
  if (name == "fisheye" || name == "equidistant")
  {
    return LensModel::Fisheye;
  }
  throwFileError(path,
    "unknown distortion_model '" + name +
      "' (expected plumb_bob or radial_tangential, OpenCV's default, or fisheye or equidistant)");
}

} // namespace

namespace
{
/// Intrinsics files hold a few numbers; anything this large is something else.
constexpr std::uintmax_t maxIntrinsicsFileBytes = 1 << 20;

/**
 * The first line (from 1) of YAML text outside the subset that OpenCV and
 * calibration tools write, 0 when every line is in it: the %YAML directive
 * and document markers at the start of a line (after a document end only a
 * directive or a new document), comments, `key: value` with a plain key,
 * block items `- value`, and any line inside an open flow list or map
 * ([ ... ], { ... }). Control characters are refused anywhere.
 */
int firstUnsupportedYamlLine(const std::string& text)
{
  std::istringstream lines(text);
  std::string line;
  int depth = 0;      // open brackets of flow collections
  bool ended = false; // after a document end marker
  for (int number = 1; std::getline(lines, line); ++number)
  {
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    for (const unsigned char c : line)
    {
      if ((c < 0x20 && c != '\t') || c == 0x7f)
      {
        return number;
      }
    }
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#')
    {
      continue;
    }
    const std::string rest = line.substr(first);
    if (ended)
    {
      // After a document end ("..."), YAML allows only directives and a new
      // document; OpenCV's parser hangs on an item there (found by fuzzing).
      if (first != 0 || (rest[0] != '%' && rest != "---" && rest.rfind("--- ", 0) != 0))
      {
        return number;
      }
      ended = false;
    }
    if (first == 0 && rest == "...")
    {
      ended = true;
      continue;
    }
    bool supported = depth > 0;
    if (!supported && first == 0)
    {
      supported = rest.rfind("%YAML", 0) == 0 || rest == "---" || rest.rfind("--- ", 0) == 0;
    }
    if (!supported)
    {
      supported = rest == "-" || rest.rfind("- ", 0) == 0;
    }
    if (!supported && (std::isalpha(static_cast<unsigned char>(rest[0])) || rest[0] == '_'))
    {
      size_t i = 1;
      while (i < rest.size() &&
        (std::isalnum(static_cast<unsigned char>(rest[i])) || rest[i] == '_' || rest[i] == '-'))
      {
        ++i;
      }
      while (i < rest.size() && rest[i] == ' ')
      {
        ++i;
      }
      supported = i < rest.size() && rest[i] == ':' && (i + 1 == rest.size() || rest[i + 1] == ' ');
    }
    if (!supported)
    {
      return number;
    }
    char quote = 0;
    for (const char c : rest)
    {
      if (quote)
      {
        quote = c == quote ? 0 : quote;
      }
      else if (c == '"' || c == '\'')
      {
        quote = c;
      }
      else if (c == '#')
      {
        break;
      }
      else if (c == '[' || c == '{')
      {
        ++depth;
      }
      else if (c == ']' || c == '}')
      {
        --depth;
      }
    }
    if (depth < 0)
    {
      return number;
    }
  }
  return 0;
}
} // namespace

bool isIntrinsicsPath(const std::string& path)
{
  const std::string ext = lowerCaseExtension(path);
  return ext == ".yaml" || ext == ".yml" || ext == ".json" || ext == ".xml";
}

PinholeCamera readIntrinsics(const std::string& path)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
  {
    throwFileError(path, "no such file");
  }
  if (!isIntrinsicsPath(path))
  {
    throwFileError(path, "unsupported intrinsics file type (expected .yaml, .yml, .json or .xml)");
  }
  {
    // OpenCV's parsers loop forever on some text holding a NUL byte (found by
    // fuzzing); intrinsics files are short text, so check before parsing.
    if (std::filesystem::file_size(path, ec) > maxIntrinsicsFileBytes)
    {
      throwFileError(path,
        "not a valid intrinsics file (larger than " + std::to_string(maxIntrinsicsFileBytes) +
          " bytes)");
    }
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find('\0') != std::string::npos)
    {
      throwFileError(
        path, "not a valid intrinsics file (it holds a NUL byte; intrinsics files are text)");
    }
    // OpenCV's YAML parser also loops forever on some malformed YAML (found
    // by fuzzing: an indented "---", lines starting "-r:"), so YAML must be
    // the subset calibration tools write before OpenCV sees it. OpenCV picks
    // the parser by the content, whatever the extension: YAML starts with
    // %YAML (after an optional UTF-8 byte order mark).
    if (text.rfind("%YAML", 0) == 0 || text.rfind("\xEF\xBB\xBF%YAML", 0) == 0)
    {
      if (const int line = firstUnsupportedYamlLine(text))
      {
        throwFileError(path,
          "not a valid intrinsics file (line " + std::to_string(line) +
            ": expected 'key: value', '- item', a comment or a continued [ ... ] list)");
      }
    }
  }
  PinholeCamera camera;
  try
  {
    cv::FileStorage storage(path, cv::FileStorage::READ);
    if (!storage.isOpened())
    {
      throwFileError(path, "cannot open the intrinsics file");
    }
    const cv::FileNode root = storage.root();
    if (!root["camera_matrix"].empty())
    {
      checkMatrixNode(root["camera_matrix"], "camera_matrix", 3, 3, path);
      cv::Mat k;
      root["camera_matrix"] >> k;
      if (k.rows != 3 || k.cols != 3)
      {
        throwFileError(path, "'camera_matrix' must be a 3x3 matrix");
      }
      k.convertTo(k, CV_64F);
      camera.fx = k.at<double>(0, 0);
      camera.fy = k.at<double>(1, 1);
      camera.cx = k.at<double>(0, 2);
      camera.cy = k.at<double>(1, 2);
      if (k.at<double>(0, 1) != 0.0 || k.at<double>(1, 0) != 0.0 || k.at<double>(2, 0) != 0.0 ||
        k.at<double>(2, 1) != 0.0 || k.at<double>(2, 2) != 1.0)
      {
        throwFileError(path, "'camera_matrix' must have the form [fx 0 cx; 0 fy cy; 0 0 1]");
      }
      camera.widthPx = static_cast<int>(readNumber(root, "image_width", path));
      camera.heightPx = static_cast<int>(readNumber(root, "image_height", path));
      if (!root["distortion_coefficients"].empty())
      {
        // OpenCV models use at most 14 coefficients, as a row or a column.
        checkMatrixNode(root["distortion_coefficients"], "distortion_coefficients", 14, 14, path);
        cv::Mat d;
        root["distortion_coefficients"] >> d;
        d.convertTo(d, CV_64F);
        d = d.reshape(1, 1);
        camera.distortion.resize(d.cols);
        for (int i = 0; i < d.cols; ++i)
        {
          camera.distortion[i] = d.at<double>(0, i);
        }
      }
    }
    else
    {
      camera.fx = readNumber(root, "fx", path);
      camera.fy = readNumber(root, "fy", path);
      camera.cx = readNumber(root, "cx", path);
      camera.cy = readNumber(root, "cy", path);
      camera.widthPx = static_cast<int>(readNumber(root, "width", path));
      camera.heightPx = static_cast<int>(readNumber(root, "height", path));
      const cv::FileNode d = root["distortion"];
      if (!d.empty())
      {
        if (!d.isSeq())
        {
          throwFileError(path, "'distortion' must be a list of numbers");
        }
        camera.distortion.resize(static_cast<Eigen::Index>(d.size()));
        for (int i = 0; i < static_cast<int>(d.size()); ++i)
        {
          camera.distortion[i] = static_cast<double>(d[i]);
        }
      }
    }
    camera.lensModel = readLensModel(root, path);
  }
  catch (const Error&)
  {
    throw;
  }
  catch (const cv::Exception& e)
  {
    throwFileError(path, "not a valid intrinsics file (" + e.err + ")");
  }
  catch (const std::exception& e)
  {
    // OpenCV's parsers also throw standard exceptions (found by fuzzing).
    throwFileError(path, std::string("not a valid intrinsics file (") + e.what() + ")");
  }
  try
  {
    camera.validate();
  }
  catch (const Error& e)
  {
    throwFileError(path, e.what());
  }
  return camera;
}

void writeIntrinsics(const PinholeCamera& camera, const std::string& path)
{
  if (!isIntrinsicsPath(path))
  {
    throwFileError(path, "unsupported intrinsics file type (expected .yaml, .yml, .json or .xml)");
  }
  try
  {
    camera.validate();
  }
  catch (const Error& e)
  {
    throwFileError(path, std::string("refusing to write invalid intrinsics: ") + e.what());
  }
  try
  {
    cv::FileStorage storage(path, cv::FileStorage::WRITE);
    if (!storage.isOpened())
    {
      throwFileError(path, "cannot write the intrinsics file");
    }
    storage << "image_width" << camera.widthPx;
    storage << "image_height" << camera.heightPx;
    const cv::Mat k = (cv::Mat_<double>(3, 3) << camera.fx, 0.0, camera.cx, 0.0, camera.fy,
      camera.cy, 0.0, 0.0, 1.0);
    storage << "camera_matrix" << k;
    cv::Mat d(1, static_cast<int>(camera.distortion.size()), CV_64F);
    for (int i = 0; i < d.cols; ++i)
    {
      d.at<double>(0, i) = camera.distortion[i];
    }
    // Only the fisheye is named, so that files of the default model stay as they were.
    if (d.cols > 0 && camera.lensModel == LensModel::Fisheye)
    {
      storage << "distortion_model"
              << "fisheye";
    }
    if (d.cols > 0)
    {
      storage << "distortion_coefficients" << d;
    }
  }
  catch (const cv::Exception& e)
  {
    throwFileError(path, "cannot write the intrinsics file (" + e.err + ")");
  }
}

} // namespace vimlop
