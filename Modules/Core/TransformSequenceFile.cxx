#include <vimlop/Core/TransformSequenceFile.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

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
          formatText("%.17g", items[i - 1].timeS) + " s, " + formatText("%.17g", items[i].timeS) +
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
      header << ' ' << formatText("%.17g", items[i].matrix(k / 4, k % 4));
    }
    header << '\n' << frame << name << "TransformStatus = OK\n";
    header << frame << "Timestamp = " << formatText("%.17g", items[i].timeS) << '\n';
  }
  header << "ElementDataFile = LOCAL\n";
  writeFileAtomically(path, header.str());
}

std::optional<double> SequenceMetafileHeader::timestampS(long frame, const std::string& path) const
{
  const auto fieldsOfFrame = this->frames.find(frame);
  if (fieldsOfFrame == this->frames.end())
  {
    return std::nullopt;
  }
  const auto value = fieldsOfFrame->second.find("Timestamp");
  if (value == fieldsOfFrame->second.end())
  {
    return std::nullopt;
  }
  std::istringstream number(value->second);
  double t = 0.0;
  if (!(number >> t) || !std::isfinite(t))
  {
    fail(path,
      "frame " + std::to_string(frame) + "'s timestamp '" + value->second + "' is not a number");
  }
  return t;
}

SequenceMetafileHeader readSequenceMetafileHeader(std::istream& in, const std::string& path)
{
  SequenceMetafileHeader header;
  std::string line;
  int lineNumber = 0;
  std::streamoff read = 0;
  while (std::getline(in, line))
  {
    ++lineNumber;
    read += static_cast<std::streamoff>(line.size()) + 1;
    if (read > (std::streamoff(64) << 20))
    {
      fail(path, "its header goes on for over 64 MiB: not a sequence metafile");
    }
    const size_t equals = line.find('=');
    if (equals == std::string::npos)
    {
      fail(path, "line " + std::to_string(lineNumber) + " is not 'name = value'");
    }
    const std::string key = trimmed(line.substr(0, equals));
    const std::string value = trimmed(line.substr(equals + 1));
    if (key.compare(0, framePrefix.size(), framePrefix) != 0)
    {
      header.fields[key] = value;
      if (key == "ElementDataFile")
      {
        header.complete = true;
        header.dataOffset = in.tellg();
        break;
      }
      continue;
    }
    const size_t underscore = key.find('_', framePrefix.size());
    char* end = nullptr;
    const std::string number = underscore == std::string::npos
      ? std::string()
      : key.substr(framePrefix.size(), underscore - framePrefix.size());
    const long frame = std::strtol(number.c_str(), &end, 10);
    if (number.empty() || *end != '\0' || frame < 0)
    {
      fail(path, "line " + std::to_string(lineNumber) + ": '" + key + "' has no frame number");
    }
    header.frames[frame][key.substr(underscore + 1)] = value;
  }
  return header;
}

std::vector<TimedTransform> readTransformSequenceFile(
  const std::string& path, const std::string& name)
{
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    fail(path, "no such file, or it cannot be read");
  }
  const SequenceMetafileHeader header = readSequenceMetafileHeader(file, path);
  if (header.fields.count("ObjectType") == 0)
  {
    fail(path, "not a sequence metafile (no ObjectType line)");
  }
  const std::string transformField = name + "Transform";
  std::vector<TimedTransform> items;
  for (const auto& [frame, fields] : header.frames)
  {
    const auto value = fields.find(transformField);
    const auto status = fields.find(transformField + "Status");
    if (value == fields.end() || (status != fields.end() && status->second != "OK"))
    {
      continue;
    }
    std::istringstream numbers(value->second);
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
      fail(path, "frame " + std::to_string(frame) + "'s " + transformField + " is not 16 numbers");
    }
    const std::optional<double> timeS = header.timestampS(frame, path);
    if (!timeS)
    {
      fail(
        path, "frame " + std::to_string(frame) + " has a " + transformField + " but no timestamp");
    }
    items.push_back({ *timeS, matrix });
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
