#include "TrackedSequenceFile.h"

#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Core/TransformSequenceFile.h>
#include <vimlop/Video/FrameSequence.h>

#include <opencv2/imgproc.hpp>

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace vimlop::detail
{

namespace
{

/// Where and how a sequence's frames are stored, from either header form.
struct FrameLayout
{
  long width = 0;
  long height = 0;
  long frames = 0;
  int channels = 1;
  /// zlib (MetaImage) or gzip (NRRD) compressed.
  bool compressed = false;
  /// Empty when the data follow the header in the same file.
  std::string dataFile;
};

std::vector<long> numbersOf(const std::string& text)
{
  std::istringstream in(text);
  std::vector<long> numbers;
  long number = 0;
  while (in >> number)
  {
    numbers.push_back(number);
  }
  return numbers;
}

void checkChannels(int channels, const std::string& path)
{
  if (channels != 1 && channels != 3 && channels != 4)
  {
    throwFileError(
      path, "frames of " + std::to_string(channels) + " channels are not read (1, 3 or 4)");
  }
}

FrameLayout metaImageLayout(const SequenceMetafileHeader& header, const std::string& path)
{
  const auto field = header.fields.find("DimSize");
  const auto dims = header.fields.find("NDims");
  if (dims == header.fields.end() || dims->second != "3" || field == header.fields.end())
  {
    throwFileError(path, "not a sequence of images (NDims must be 3: width, height and frames)");
  }
  const std::vector<long> sizes = numbersOf(field->second);
  if (sizes.size() != 3 || sizes[0] < 1 || sizes[1] < 1 || sizes[2] < 1)
  {
    throwFileError(path, "DimSize '" + field->second + "' is not three positive sizes");
  }
  const auto type = header.fields.find("ElementType");
  if (type == header.fields.end() || type->second != "MET_UCHAR")
  {
    throwFileError(path,
      "its pixels are " + (type == header.fields.end() ? "of no type" : type->second) +
        "; a tracked video needs 8-bit pixels (MET_UCHAR)");
  }
  FrameLayout layout;
  layout.width = sizes[0];
  layout.height = sizes[1];
  layout.frames = sizes[2];
  if (const auto channels = header.fields.find("ElementNumberOfChannels");
      channels != header.fields.end())
  {
    layout.channels = std::atoi(channels->second.c_str());
    checkChannels(layout.channels, path);
  }
  const auto compressed = header.fields.find("CompressedData");
  layout.compressed = compressed != header.fields.end() && lowerCase(compressed->second) == "true";
  const std::string where = header.fields.at("ElementDataFile");
  if (where != "LOCAL")
  {
    if (where.find(' ') != std::string::npos || where == "LIST")
    {
      throwFileError(path, "data in several files (ElementDataFile '" + where + "') is not read");
    }
    layout.dataFile = where;
  }
  return layout;
}

/// PLUS writes `sizes: 3 640 480 1 30` with `kinds: vector domain domain
/// domain list`; Slicer the same with RGB-color, or no component axis for grey.
FrameLayout nrrdLayout(const SequenceMetafileHeader& header, const std::string& path)
{
  const auto field = [&](const std::string& name)
  {
    const auto found = header.fields.find(name);
    return found == header.fields.end() ? std::string() : found->second;
  };
  const std::string type = field("type");
  if (type != "uchar" && type != "unsigned char" && type != "uint8" && type != "uint8_t")
  {
    throwFileError(path,
      "its pixels are " + (type.empty() ? "of no type" : "'" + type + "'") +
        "; a tracked video needs 8-bit pixels (uchar)");
  }
  const std::vector<long> sizes = numbersOf(field("sizes"));
  std::istringstream kindList(field("kinds"));
  std::vector<std::string> kinds;
  for (std::string kind; kindList >> kind;)
  {
    kinds.push_back(kind);
  }
  if (kinds.size() != sizes.size() || sizes.size() < 3)
  {
    throwFileError(path,
      "its sizes '" + field("sizes") + "' and kinds '" + field("kinds") +
        "' do not name a sequence of images (e.g. sizes: 3 640 480 1 30, kinds: vector domain "
        "domain domain list)");
  }
  FrameLayout layout;
  std::vector<long> spatial;
  for (size_t axis = 0; axis < kinds.size(); ++axis)
  {
    const std::string kind = lowerCase(kinds[axis]);
    if (axis + 1 == kinds.size())
    {
      if (kind != "list" && kind != "time" && kind != "none" && kind != "???")
      {
        throwFileError(
          path, "its last axis is of kind '" + kinds[axis] + "', not a list of frames");
      }
      layout.frames = sizes[axis];
    }
    else if (kind == "domain" || kind == "space")
    {
      spatial.push_back(sizes[axis]);
    }
    else if (axis == 0)
    {
      layout.channels = static_cast<int>(sizes[0]);
    }
    else
    {
      throwFileError(
        path, "its axis " + std::to_string(axis) + " is of kind '" + kinds[axis] + "'");
    }
  }
  checkChannels(layout.channels, path);
  if (spatial.size() == 3 && spatial[2] == 1)
  {
    spatial.pop_back();
  }
  if (spatial.size() != 2 || spatial[0] < 1 || spatial[1] < 1 || layout.frames < 1)
  {
    throwFileError(path, "its frames are not 2-D images (sizes '" + field("sizes") + "')");
  }
  layout.width = spatial[0];
  layout.height = spatial[1];
  const std::string encoding = lowerCase(field("encoding"));
  if (encoding != "raw" && encoding != "gzip" && encoding != "gz")
  {
    throwFileError(
      path, "its data are in '" + field("encoding") + "' encoding; raw and gzip are read");
  }
  layout.compressed = encoding != "raw";
  layout.dataFile = field("data file").empty() ? field("datafile") : field("data file");
  if (layout.dataFile.find(' ') != std::string::npos ||
    layout.dataFile.find('%') != std::string::npos)
  {
    throwFileError(path, "data in several files (data file '" + layout.dataFile + "') is not read");
  }
  return layout;
}

/// The pixel bytes of the whole sequence, inflated when compressed.
std::string dataOf(std::ifstream& file, const SequenceMetafileHeader& header,
  const FrameLayout& layout, const std::string& path, std::uint64_t expectedBytes)
{
  std::ifstream external;
  std::istream* in = &file;
  if (layout.dataFile.empty())
  {
    file.seekg(header.dataOffset);
  }
  else
  {
    const std::filesystem::path data = std::filesystem::path(path).parent_path() / layout.dataFile;
    external.open(data, std::ios::binary);
    if (!external)
    {
      throwFileError(path, "its data file '" + data.string() + "' cannot be read");
    }
    in = &external;
  }
  // Uncompressed, only the frames needed are read; compressed, the stream
  // is read whole (a compressed file is smaller than its frames).
  std::string raw;
  if (!layout.compressed)
  {
    raw.resize(static_cast<size_t>(expectedBytes));
    in->read(raw.data(), static_cast<std::streamsize>(expectedBytes));
    raw.resize(static_cast<size_t>(in->gcount()));
    return raw;
  }
  raw.assign(std::istreambuf_iterator<char>(*in), std::istreambuf_iterator<char>());
  std::string inflated(static_cast<size_t>(expectedBytes), '\0');
  z_stream stream{};
  // 32 + 15: a zlib (MetaImage) or gzip (NRRD) header, told by zlib.
  int status = inflateInit2(&stream, 32 + 15);
  stream.next_in = reinterpret_cast<Bytef*>(raw.data());
  stream.avail_in = static_cast<uInt>(raw.size());
  stream.next_out = reinterpret_cast<Bytef*>(inflated.data());
  stream.avail_out = static_cast<uInt>(inflated.size());
  if (status == Z_OK)
  {
    status = inflate(&stream, Z_FINISH);
  }
  const std::uint64_t length = stream.total_out;
  inflateEnd(&stream);
  if (status != Z_STREAM_END && status != Z_BUF_ERROR &&
    !(status == Z_OK && length == expectedBytes))
  {
    throwFileError(
      path, "its compressed data does not inflate (zlib error " + std::to_string(status) + ")");
  }
  inflated.resize(static_cast<size_t>(length));
  return inflated;
}

} // namespace

bool isTrackedSequencePath(const std::string& path)
{
  std::error_code error;
  return FrameSequence::isTrackedSequenceName(path) &&
    std::filesystem::is_regular_file(path, error);
}

TrackedSequenceFrames readTrackedSequence(const std::string& path, int maxFrames,
  const std::function<void(int, std::uint64_t, std::uint64_t)>& checkSize)
{
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    throwFileError(path, "cannot be read");
  }
  const SequenceMetafileHeader header = readSequenceMetafileHeader(file, path);
  if (!header.complete)
  {
    throwFileError(path,
      header.format == SequenceFileFormat::Nrrd
        ? "its NRRD header has no blank line before the data"
        : "not a MetaImage (no ElementDataFile line ends its header)");
  }
  const FrameLayout layout = header.format == SequenceFileFormat::Nrrd
    ? nrrdLayout(header, path)
    : metaImageLayout(header, path);
  const int channels = layout.channels;
  // Which frames, and the size check, before any pixel is read.
  std::vector<long> kept;
  for (long frame = 0; frame < layout.frames && static_cast<int>(kept.size()) < maxFrames; ++frame)
  {
    const auto fields = header.frames.find(frame);
    if (fields != header.frames.end())
    {
      const auto status = fields->second.find("ImageStatus");
      if (status != fields->second.end() && status->second != "OK")
      {
        continue;
      }
    }
    if (!header.timestampS(frame, path))
    {
      throwFileError(path,
        "frame " + std::to_string(frame) + " has no Seq_Frame" + std::to_string(frame) +
          "_Timestamp" +
          (header.format == SequenceFileFormat::Nrrd ? " and no sequence index value (axis 3 "
                                                       "index values, in seconds)"
                                                     : ""));
    }
    checkSize(static_cast<int>(kept.size()), static_cast<std::uint64_t>(layout.width),
      static_cast<std::uint64_t>(layout.height));
    kept.push_back(frame);
  }
  if (kept.empty())
  {
    throwFileError(path, "holds no frame whose image status is OK");
  }
  const std::uint64_t frameBytes =
    static_cast<std::uint64_t>(layout.width) * static_cast<std::uint64_t>(layout.height) * channels;
  const std::uint64_t neededBytes = frameBytes * static_cast<std::uint64_t>(kept.back() + 1);
  if (neededBytes > FrameSequence::MaxDecodedBytes)
  {
    throwFileError(path,
      "its frames up to frame " + std::to_string(kept.back()) + " take " +
        std::to_string(neededBytes >> 20) + " MiB, more than the " +
        std::to_string(FrameSequence::MaxDecodedBytes >> 20) + " MiB a sequence may take");
  }
  const std::string data = dataOf(file, header, layout, path, neededBytes);
  if (data.size() < neededBytes)
  {
    throwFileError(path,
      "its data ends inside frame " + std::to_string(data.size() / frameBytes) + " (" +
        std::to_string(data.size()) + " of " + std::to_string(neededBytes) + " bytes)");
  }

  TrackedSequenceFrames sequence;
  for (const long frame : kept)
  {
    const double timeS = *header.timestampS(frame, path);
    if (!sequence.timestampsS.empty() && !(timeS > sequence.timestampsS.back()))
    {
      throwFileError(path,
        "the timestamps do not increase: frame " + std::to_string(frame) + " is at " +
          std::to_string(timeS) + " s, the frame before it at " +
          std::to_string(sequence.timestampsS.back()) + " s");
    }
    const cv::Mat pixels(static_cast<int>(layout.height), static_cast<int>(layout.width),
      CV_8UC(channels),
      const_cast<char*>(data.data() + frameBytes * static_cast<std::uint64_t>(frame)));
    cv::Mat bgr;
    if (channels == 1)
    {
      cv::cvtColor(pixels, bgr, cv::COLOR_GRAY2BGR);
    }
    else
    {
      cv::cvtColor(pixels, bgr, channels == 3 ? cv::COLOR_RGB2BGR : cv::COLOR_RGBA2BGR);
    }
    sequence.frames.push_back(bgr);
    sequence.numbers.push_back(static_cast<int>(frame));
    sequence.timestampsS.push_back(timeS);
  }
  return sequence;
}

} // namespace vimlop::detail
