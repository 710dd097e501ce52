#include <vimlop/Video/FrameSequence.h>

#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>

#include "FrameFiles.h"
#include "ImageFileHeader.h"
#include "TrackedSequenceFile.h"
#include "VideoFileDecoder.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace vimlop
{

using detail::checkFrameSize;
using detail::decodeImage;
using detail::idsOf;
using detail::toBGR8;

std::string FrameSequence::idGaps() const
{
  std::string gaps;
  for (std::size_t i = 1; i < this->Ids.size(); ++i)
  {
    const int from = this->Ids[i - 1] + 1;
    const int to = this->Ids[i] - 1;
    if (to < from)
    {
      continue;
    }
    gaps += (gaps.empty() ? "" : ", ") +
      (from == to ? "frame " + std::to_string(from)
                  : "frames " + std::to_string(from) + " to " + std::to_string(to)) +
      " (between '" + this->Names[i - 1] + "' and '" + this->Names[i] + "')";
  }
  return gaps;
}

bool FrameSequence::isImageFileName(const std::string& name)
{
  const std::string ext = lowerCaseExtension(name);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tif" ||
    ext == ".tiff";
}

bool FrameSequence::isTrackedSequenceName(const std::string& name)
{
  const std::string ext = lowerCaseExtension(name);
  return ext == ".mha" || ext == ".mhd" || ext == ".nrrd" || ext == ".nhdr";
}

FrameSequence FrameSequence::load(const std::string& path, int maxFrames)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec))
  {
    throwFileError(path, "no such file or folder");
  }
  if (maxFrames < 1)
  {
    throwFileError(path, "the number of frames to load must be at least 1");
  }
  FrameSequence sequence;
  if (fs::is_directory(path, ec))
  {
    std::vector<std::string> names = detail::imageFileNamesIn(path);
    names.resize(std::min(names.size(), static_cast<size_t>(maxFrames)));
    // Every header first: a sequence too large is refused before any decoding.
    std::uint64_t decodedBytes = 0;
    std::vector<bool> judged(names.size());
    for (std::size_t i = 0; i < names.size(); ++i)
    {
      const ImageFileHeader header = readImageFileHeader((fs::path(path) / names[i]).string());
      if ((judged[i] = header.known))
      {
        checkFrameSize(
          path, names[i], header.widthPx, header.heightPx, static_cast<int>(i), decodedBytes);
      }
    }
    for (std::size_t i = 0; i < names.size(); ++i)
    {
      const std::string file = (fs::path(path) / names[i]).string();
      const cv::Mat image = decodeImage(file);
      if (!judged[i])
      {
        checkFrameSize(path, names[i], static_cast<std::uint64_t>(image.cols),
          static_cast<std::uint64_t>(image.rows), static_cast<int>(i), decodedBytes);
      }
      sequence.Frames.push_back(toBGR8(image));
      sequence.Names.push_back(names[i]);
    }
  }
  else if (detail::isTrackedSequencePath(path))
  {
    std::uint64_t decodedBytes = 0;
    detail::TrackedSequenceFrames tracked = detail::readTrackedSequence(path, maxFrames,
      [&](int index, std::uint64_t width, std::uint64_t height) {
        checkFrameSize(path, "frame" + std::to_string(index), width, height, index, decodedBytes);
      });
    sequence.Frames = std::move(tracked.frames);
    for (const int number : tracked.numbers)
    {
      sequence.Names.push_back("frame" + std::to_string(number));
    }
    sequence.TimestampsS = std::move(tracked.timestampsS);
    const std::vector<double>& t = sequence.TimestampsS;
    if (t.size() > 1 && t.back() > t.front())
    {
      sequence.FramesPerSecond =
        (tracked.numbers.back() - tracked.numbers.front()) / (t.back() - t.front());
    }
  }
  else
  {
    // Decoded in a child process; each frame is judged on its size before
    // its pixels are read, the memory budget on the frames as they come.
    std::uint64_t decodedBytes = 0;
    sequence.Frames = detail::decodeVideoFile(path, maxFrames, detail::videoDecoderProgram(),
      [&](int index, std::uint64_t width, std::uint64_t height) {
        checkFrameSize(path, "frame" + std::to_string(index), width, height, index, decodedBytes);
      });
    for (int i = 0; i < sequence.size(); ++i)
    {
      sequence.Names.push_back("frame" + std::to_string(i));
    }
    sequence.FramesPerSecond = detail::videoFramesPerSecond(path);
  }
  sequence.Ids = idsOf(sequence.Names);
  for (int i = 1; i < sequence.size(); ++i)
  {
    if (sequence.Frames[i].size() != sequence.Frames[0].size())
    {
      throwFileError(path,
        "frame '" + sequence.Names[i] + "' is " + std::to_string(sequence.Frames[i].cols) + "x" +
          std::to_string(sequence.Frames[i].rows) + " but '" + sequence.Names[0] + "' is " +
          std::to_string(sequence.widthPx()) + "x" + std::to_string(sequence.heightPx()));
    }
  }
  return sequence;
}

} // namespace vimlop
