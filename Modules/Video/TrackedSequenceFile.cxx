#include "TrackedSequenceFile.h"

#include <vimlop/Core/Error.h>
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

[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw Error("'" + path + "': " + problem);
}

std::vector<long> dimensionsOf(const SequenceMetafileHeader& header, const std::string& path)
{
  const auto field = header.fields.find("DimSize");
  const auto dims = header.fields.find("NDims");
  if (dims == header.fields.end() || dims->second != "3" || field == header.fields.end())
  {
    fail(path, "not a sequence of images (NDims must be 3: width, height and frames)");
  }
  std::istringstream text(field->second);
  std::vector<long> sizes;
  long size = 0;
  while (text >> size)
  {
    sizes.push_back(size);
  }
  if (sizes.size() != 3 || sizes[0] < 1 || sizes[1] < 1 || sizes[2] < 1)
  {
    fail(path, "DimSize '" + field->second + "' is not three positive sizes");
  }
  return sizes;
}

/// The pixel bytes of the whole sequence, inflated when compressed.
std::string dataOf(std::ifstream& file, const SequenceMetafileHeader& header,
  const std::string& path, std::uint64_t expectedBytes)
{
  const std::string where = header.fields.at("ElementDataFile");
  const auto compressed = header.fields.find("CompressedData");
  const bool inflate = compressed != header.fields.end() && lowerCase(compressed->second) == "true";
  std::ifstream external;
  std::istream* in = &file;
  if (where == "LOCAL")
  {
    file.seekg(header.dataOffset);
  }
  else
  {
    if (where.find(' ') != std::string::npos || where == "LIST")
    {
      fail(path, "data in several files (ElementDataFile '" + where + "') is not read");
    }
    const std::filesystem::path data = std::filesystem::path(path).parent_path() / where;
    external.open(data, std::ios::binary);
    if (!external)
    {
      fail(path, "its data file '" + data.string() + "' cannot be read");
    }
    in = &external;
  }
  // Uncompressed, only the frames needed are read; compressed, the stream
  // is read whole (a compressed file is smaller than its frames).
  std::string raw;
  if (!inflate)
  {
    raw.resize(static_cast<size_t>(expectedBytes));
    in->read(raw.data(), static_cast<std::streamsize>(expectedBytes));
    raw.resize(static_cast<size_t>(in->gcount()));
    return raw;
  }
  raw.assign(std::istreambuf_iterator<char>(*in), std::istreambuf_iterator<char>());
  std::string inflated(static_cast<size_t>(expectedBytes), '\0');
  uLongf length = static_cast<uLongf>(expectedBytes);
  const int status = uncompress(reinterpret_cast<Bytef*>(inflated.data()), &length,
    reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size()));
  if (status != Z_OK && status != Z_BUF_ERROR)
  {
    fail(path, "its compressed data does not inflate (zlib error " + std::to_string(status) + ")");
  }
  inflated.resize(length);
  return inflated;
}

} // namespace

bool isTrackedSequencePath(const std::string& path)
{
  const std::string ext = lowerCaseExtension(path);
  std::error_code error;
  return (ext == ".mha" || ext == ".mhd") && std::filesystem::is_regular_file(path, error);
}

TrackedSequenceFrames readTrackedSequence(const std::string& path, int maxFrames,
  const std::function<void(int, std::uint64_t, std::uint64_t)>& checkSize)
{
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    fail(path, "cannot be read");
  }
  const SequenceMetafileHeader header = readSequenceMetafileHeader(file, path);
  if (!header.complete)
  {
    fail(path, "not a MetaImage (no ElementDataFile line ends its header)");
  }
  const std::vector<long> sizes = dimensionsOf(header, path);
  const auto type = header.fields.find("ElementType");
  if (type == header.fields.end() || type->second != "MET_UCHAR")
  {
    fail(path,
      "its pixels are " + (type == header.fields.end() ? "of no type" : type->second) +
        "; a tracked video needs 8-bit pixels (MET_UCHAR)");
  }
  int channels = 1;
  if (const auto field = header.fields.find("ElementNumberOfChannels");
      field != header.fields.end())
  {
    channels = std::atoi(field->second.c_str());
    if (channels != 1 && channels != 3 && channels != 4)
    {
      fail(path, "frames of " + field->second + " channels are not read (1, 3 or 4)");
    }
  }
  // Which frames, and the size check, before any pixel is read.
  std::vector<long> kept;
  for (long frame = 0; frame < sizes[2] && static_cast<int>(kept.size()) < maxFrames; ++frame)
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
      fail(path,
        "frame " + std::to_string(frame) + " has no Seq_Frame" + std::to_string(frame) +
          "_Timestamp");
    }
    checkSize(static_cast<int>(kept.size()), static_cast<std::uint64_t>(sizes[0]),
      static_cast<std::uint64_t>(sizes[1]));
    kept.push_back(frame);
  }
  if (kept.empty())
  {
    fail(path, "holds no frame whose image status is OK");
  }
  const std::uint64_t frameBytes =
    static_cast<std::uint64_t>(sizes[0]) * static_cast<std::uint64_t>(sizes[1]) * channels;
  const std::uint64_t neededBytes = frameBytes * static_cast<std::uint64_t>(kept.back() + 1);
  if (neededBytes > FrameSequence::MaxDecodedBytes)
  {
    fail(path,
      "its frames up to frame " + std::to_string(kept.back()) + " take " +
        std::to_string(neededBytes >> 20) + " MiB, more than the " +
        std::to_string(FrameSequence::MaxDecodedBytes >> 20) + " MiB a sequence may take");
  }
  const std::string data = dataOf(file, header, path, neededBytes);
  if (data.size() < neededBytes)
  {
    fail(path,
      "its data ends inside frame " + std::to_string(data.size() / frameBytes) + " (" +
        std::to_string(data.size()) + " of " + std::to_string(neededBytes) + " bytes)");
  }

  TrackedSequenceFrames sequence;
  for (const long frame : kept)
  {
    const double timeS = *header.timestampS(frame, path);
    if (!sequence.timestampsS.empty() && !(timeS > sequence.timestampsS.back()))
    {
      fail(path,
        "the timestamps do not increase: frame " + std::to_string(frame) + " is at " +
          std::to_string(timeS) + " s, the frame before it at " +
          std::to_string(sequence.timestampsS.back()) + " s");
    }
    const cv::Mat pixels(static_cast<int>(sizes[1]), static_cast<int>(sizes[0]), CV_8UC(channels),
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
