#include <vimlop/Core/TransformSequenceFile.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

namespace vimlop
{

namespace
{

[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw Error("'" + path + "': " + problem);
}

std::string trimmed(const std::string& text)
{
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos)
  {
    return "";
  }
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

std::string exact(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

const std::string framePrefix = "Seq_Frame";

} // namespace

void writeTransformSequenceFile(
  const std::vector<TimedTransform>& items, const std::string& name, const std::string& path)
{
  if (items.empty())
  {
    fail(path, "the transform sequence to write is empty");
  }
  if (name.empty() ||
    !std::all_of(name.begin(), name.end(), [](unsigned char c) { return std::isalnum(c); }))
  {
    fail(path, "the transform name '" + name + "' is not letters and digits");
  }
  for (size_t i = 0; i < items.size(); ++i)
  {
    if (!std::isfinite(items[i].timeS) || !items[i].matrix.allFinite())
    {
      fail(path, "item " + std::to_string(i) + " of the sequence has a value that is not finite");
    }
    // Slicer indexes the items by their time rounded to the millisecond.
    if (i > 0 && items[i].timeS - items[i - 1].timeS < 1e-3)
    {
      fail(path,
        "the times of items " + std::to_string(i - 1) + " and " + std::to_string(i) + " (" +
          exact(items[i - 1].timeS) + " s, " + exact(items[i].timeS) +
          " s) do not increase by at least 1 ms");
    }
  }
  std::ostringstream header;
  header << "ObjectType = Image\nNDims = 3\nAnatomicalOrientation = RAI\nBinaryData = True\n"
            "CompressedData = False\nDimSize = 0 0 "
         << items.size()
         << "\nElementSpacing = 1 1 1\nOffset = 0 0 0\nTransformMatrix = 1 0 0 0 1 0 0 0 1\n"
            "ElementType = MET_UCHAR\nKinds = domain domain list\n";
  for (size_t i = 0; i < items.size(); ++i)
  {
    char frame[32];
    std::snprintf(frame, sizeof(frame), "%s%04zu_", framePrefix.c_str(), i);
    header << frame << name << "Transform =";
    for (int k = 0; k < 16; ++k)
    {
      header << ' ' << exact(items[i].matrix(k / 4, k % 4));
    }
    header << '\n' << frame << name << "TransformStatus = OK\n";
    header << frame << "Timestamp = " << exact(items[i].timeS) << '\n';
  }
  header << "ElementDataFile = LOCAL\n";
  writeFileAtomically(path, header.str());
}

std::vector<TimedTransform> readTransformSequenceFile(
  const std::string& path, const std::string& name)
{
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    fail(path, "no such file, or it cannot be read");
  }
  struct Frame
  {
    std::optional<Eigen::Matrix4d> matrix;
    std::optional<double> timeS;
    bool ok = true;
  };
  std::map<long, Frame> frames;
  const std::string transformField = name + "Transform";
  bool sawObjectType = false;
  std::string line;
  int lineNumber = 0;
  while (std::getline(file, line))
  {
    ++lineNumber;
    const size_t equals = line.find('=');
    if (equals == std::string::npos)
    {
      fail(path, "line " + std::to_string(lineNumber) + " is not 'name = value'");
    }
    const std::string key = trimmed(line.substr(0, equals));
    const std::string value = trimmed(line.substr(equals + 1));
    if (key == "ObjectType")
    {
      sawObjectType = true;
    }
    if (key == "ElementDataFile")
    {
      break; // the voxels (if any) follow; the header ends here
    }
    if (key.compare(0, framePrefix.size(), framePrefix) != 0)
    {
      continue;
    }
    const size_t underscore = key.find('_', framePrefix.size());
    if (underscore == std::string::npos)
    {
      continue;
    }
    char* end = nullptr;
    const std::string number = key.substr(framePrefix.size(), underscore - framePrefix.size());
    const long index = std::strtol(number.c_str(), &end, 10);
    if (number.empty() || *end != '\0' || index < 0)
    {
      fail(path, "line " + std::to_string(lineNumber) + ": '" + key + "' has no frame number");
    }
    const std::string field = key.substr(underscore + 1);
    Frame& frame = frames[index];
    if (field == transformField)
    {
      std::istringstream numbers(value);
      Eigen::Matrix4d matrix;
      int count = 0;
      double v = 0.0;
      while (numbers >> v)
      {
        if (count < 16)
        {
          matrix(count / 4, count % 4) = v;
        }
        ++count;
      }
      if (count != 16 || !numbers.eof() || !matrix.allFinite())
      {
        fail(path, "line " + std::to_string(lineNumber) + ": '" + key + "' is not 16 numbers");
      }
      frame.matrix = matrix;
    }
    else if (field == transformField + "Status")
    {
      frame.ok = value == "OK";
    }
    else if (field == "Timestamp")
    {
      std::istringstream number(value);
      double t = 0.0;
      if (!(number >> t) || !std::isfinite(t))
      {
        fail(path,
          "line " + std::to_string(lineNumber) + ": the timestamp '" + value + "' is not a number");
      }
      frame.timeS = t;
    }
  }
  if (!sawObjectType)
  {
    fail(path, "not a sequence metafile (no ObjectType line)");
  }
  std::vector<TimedTransform> items;
  for (const auto& [index, frame] : frames)
  {
    if (!frame.matrix || !frame.ok)
    {
      continue;
    }
    if (!frame.timeS)
    {
      fail(
        path, "frame " + std::to_string(index) + " has a " + transformField + " but no timestamp");
    }
    items.push_back({ *frame.timeS, *frame.matrix });
  }
  if (items.empty())
  {
    fail(path,
      "holds no frame of the transform '" + name + "' (no field Seq_Frame<n>_" + transformField +
        " with status OK)");
  }
  return items;
}

} // namespace vimlop
