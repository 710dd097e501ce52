#include <vimlop/Core/TransformSequenceFile.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/FileError.h>
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

const std::string framePrefix = "Seq_Frame";

/// Files a `Seq_Frame<n>_<name>` field under frame n, any other as the header's own.
void addField(SequenceMetafileHeader& header, const std::string& key, const std::string& value,
  int lineNumber, const std::string& path)
{
  if (key.compare(0, framePrefix.size(), framePrefix) != 0)
  {
    header.fields[key] = value;
    return;
  }
  const size_t underscore = key.find('_', framePrefix.size());
  char* end = nullptr;
  const std::string number = underscore == std::string::npos
    ? std::string()
    : key.substr(framePrefix.size(), underscore - framePrefix.size());
  const long frame = std::strtol(number.c_str(), &end, 10);
  if (number.empty() || *end != '\0' || frame < 0)
  {
    throwFileError(
      path, "line " + std::to_string(lineNumber) + ": '" + key + "' has no frame number");
  }
  header.frames[frame][key.substr(underscore + 1)] = value;
}

/// The last of a NRRD per-axis field's quoted strings (`units: "" "" "" "s"`):
/// the sequence axis is the last one.
std::string lastQuoted(const std::string& text)
{
  const size_t close = text.rfind('"');
  const size_t open =
    close == std::string::npos || close == 0 ? std::string::npos : text.rfind('"', close - 1);
  return open == std::string::npos ? std::string() : text.substr(open + 1, close - open - 1);
}

/// Slicer's volume sequences carry their times as the sequence axis's index
/// values, not as frame fields: they become the frames' Timestamps.
void timestampsFromSequenceIndex(SequenceMetafileHeader& header, const std::string& path)
{
  for (const auto& [frame, fields] : header.frames)
  {
    if (fields.count("Timestamp"))
    {
      return;
    }
  }
  for (const auto& [key, values] : header.fields)
  {
    const size_t suffix = key.rfind(" index values");
    if (key.compare(0, 5, "axis ") != 0 || suffix == std::string::npos || suffix + 13 != key.size())
    {
      continue;
    }
    const std::string axis = key.substr(0, suffix);
    const auto type = header.fields.find(axis + " index type");
    if (type != header.fields.end() && type->second != "numeric")
    {
      throwFileError(path,
        "its sequence index is of type '" + type->second +
          "', not numeric: the frames have no times");
    }
    const auto units = header.fields.find("units");
    const std::string unit = units == header.fields.end() ? "" : lastQuoted(units->second);
    if (!unit.empty() && unit != "s")
    {
      throwFileError(path, "its sequence index is in '" + unit + "', not in seconds (s)");
    }
    std::istringstream list(values);
    std::string value;
    for (long frame = 0; list >> value; ++frame)
    {
      header.frames[frame]["Timestamp"] = value;
    }
    return;
  }
}

} // namespace

void writeTransformSequenceFile(
  const std::vector<TimedTransform>& items, const std::string& name, const std::string& path)
{
  if (items.empty())
  {
    throwFileError(path, "the transform sequence to write is empty");
  }
  if (name.empty() ||
    !std::all_of(name.begin(), name.end(), [](unsigned char c) { return std::isalnum(c); }))
  {
    throwFileError(path, "the transform name '" + name + "' is not letters and digits");
  }
  for (size_t i = 0; i < items.size(); ++i)
  {
    if (!std::isfinite(items[i].timeS) || !items[i].matrix.allFinite())
    {
      throwFileError(
        path, "item " + std::to_string(i) + " of the sequence has a value that is not finite");
    }
    // Slicer indexes the items by their time rounded to the millisecond.
    if (i > 0 && items[i].timeS - items[i - 1].timeS < 1e-3)
    {
      throwFileError(path,
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
    throwFileError(path,
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
      throwFileError(path, "its header goes on for over 64 MiB: not a sequence metafile");
    }
    if (lineNumber == 1 && line.compare(0, 7, "NRRD000") == 0)
    {
      header.format = SequenceFileFormat::Nrrd;
      continue;
    }
    if (header.format == SequenceFileFormat::Nrrd)
    {
      if (line.empty() || line == "\r")
      {
        header.complete = true;
        header.dataOffset = in.tellg();
        break;
      }
      if (line[0] == '#')
      {
        continue;
      }
      const size_t keyEnd = line.find(":=");
      const size_t fieldEnd = line.find(": ");
      const size_t colon = std::min(keyEnd, fieldEnd);
      if (colon == std::string::npos)
      {
        throwFileError(
          path, "line " + std::to_string(lineNumber) + " is not 'field: value' or 'key:=value'");
      }
      addField(
        header, trimmed(line.substr(0, colon)), trimmed(line.substr(colon + 2)), lineNumber, path);
      continue;
    }
    const size_t equals = line.find('=');
    if (equals == std::string::npos)
    {
      throwFileError(path, "line " + std::to_string(lineNumber) + " is not 'name = value'");
    }
    const std::string key = trimmed(line.substr(0, equals));
    addField(header, key, trimmed(line.substr(equals + 1)), lineNumber, path);
    if (key == "ElementDataFile")
    {
      header.complete = true;
      header.dataOffset = in.tellg();
      break;
    }
  }
  if (header.format == SequenceFileFormat::Nrrd)
  {
    timestampsFromSequenceIndex(header, path);
  }
  return header;
}

std::vector<TimedTransform> readTransformSequenceFile(
  const std::string& path, const std::string& name)
{
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    throwFileError(path, "no such file, or it cannot be read");
  }
  const SequenceMetafileHeader header = readSequenceMetafileHeader(file, path);
  if (header.format == SequenceFileFormat::MetaImage && header.fields.count("ObjectType") == 0)
  {
    throwFileError(path, "not a sequence metafile (no ObjectType line)");
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
      throwFileError(
        path, "frame " + std::to_string(frame) + "'s " + transformField + " is not 16 numbers");
    }
    const std::optional<double> timeS = header.timestampS(frame, path);
    if (!timeS)
    {
      throwFileError(
        path, "frame " + std::to_string(frame) + " has a " + transformField + " but no timestamp");
    }
    items.push_back({ *timeS, matrix });
  }
  if (items.empty())
  {
    const bool anyTransform = std::any_of(header.frames.begin(), header.frames.end(),
      [](const auto& frame)
      {
        return std::any_of(frame.second.begin(), frame.second.end(),
          [](const auto& field) { return field.first.find("Transform") != std::string::npos; });
      });
    throwFileError(path,
      "holds no frame of the transform '" + name + "' (no field Seq_Frame<n>_" + transformField +
        " with status OK)" +
        (anyTransform || header.format != SequenceFileFormat::Nrrd
            ? ""
            : "; it holds no transform at all, as a 3D Slicer volume sequence: Slicer saves a "
              "transform's sequence in its own file (.seq.mha)"));
  }
  return items;
}

} // namespace vimlop
