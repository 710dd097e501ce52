#include <vimlop/Video/FrameSequence.h>

#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>

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

namespace
{

/// "frame2" < "frame10": digit runs compare by value, the rest by character.
bool naturalLess(const std::string& a, const std::string& b)
{
  size_t i = 0;
  size_t j = 0;
  while (i < a.size() && j < b.size())
  {
    if (std::isdigit(static_cast<unsigned char>(a[i])) &&
      std::isdigit(static_cast<unsigned char>(b[j])))
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
      // Compare numerically without overflow: strip leading zeros, then by length.
      size_t ia = a.find_first_not_of('0', i);
      size_t jb = b.find_first_not_of('0', j);
      ia = (ia == std::string::npos || ia > ie) ? ie : ia;
      jb = (jb == std::string::npos || jb > je) ? je : jb;
      if (ie - ia != je - jb)
      {
        return ie - ia < je - jb;
      }
      const int c = a.compare(ia, ie - ia, b, jb, je - jb);
      if (c != 0)
      {
        return c < 0;
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

/// One image file decoded; OpenCV's decoders throw on some broken files
/// (an image larger than their own limit, say) where others return nothing.
cv::Mat decodeImage(const std::string& file)
{
  cv::Mat image;
  try
  {
    image = cv::imread(file, cv::IMREAD_UNCHANGED);
  }
  catch (const cv::Exception& e)
  {
    throwFileError(file, "not a readable image (OpenCV: " + e.err + ")");
  }
  if (image.empty())
  {
    throwFileError(file, "not a readable image");
  }
  return image;
}

cv::Mat toBGR8(const cv::Mat& image)
{
  cv::Mat out = image;
  if (out.depth() != CV_8U)
  {
    // 16-bit frames (some endoscope grabbers) are scaled down to 8 bits.
    out.convertTo(out, CV_8U, out.depth() == CV_16U ? 1.0 / 256.0 : 1.0);
  }
  if (out.channels() == 1)
  {
    cv::cvtColor(out, out, cv::COLOR_GRAY2BGR);
  }
  else if (out.channels() == 4)
  {
    cv::cvtColor(out, out, cv::COLOR_BGRA2BGR);
  }
  return out;
}

/// Refuses a frame of `width` x `height` pixels before it is decoded when it
/// is larger than any endoscope's, or when it would take the sequence past
/// its memory budget; `decodedBytes` counts the frames so far.
void checkFrameSize(const std::string& path, const std::string& name, std::uint64_t width,
  std::uint64_t height, int framesSoFar, std::uint64_t& decodedBytes)
{
  if (width * height > FrameSequence::MaxFramePixels || width > 65535 || height > 65535)
  {
    throwFileError(path,
      "frame '" + name + "' is " + std::to_string(width) + " x " + std::to_string(height) +
        " pixels; frames of at most " + std::to_string(FrameSequence::MaxFramePixels) +
        " pixels (8192 x 8192) are read");
  }
  decodedBytes += width * height * 3;
  if (decodedBytes > FrameSequence::MaxDecodedBytes)
  {
    throwFileError(path,
      "the first " + std::to_string(framesSoFar + 1) + " frames of " + std::to_string(width) +
        " x " + std::to_string(height) + " pixels would take more than " +
        std::to_string(FrameSequence::MaxDecodedBytes >> 30) +
        " GiB decoded; read fewer (--max-frames)");
  }
}

/// The last run of digits in a file name's stem ("frame011.png": 11), or -1
/// when there is none or it does not fit an int.
int numberInName(const std::string& name)
{
  const std::string stem = std::filesystem::path(name).stem().string();
  const auto last = stem.find_last_of("0123456789");
  if (last == std::string::npos)
  {
    return -1;
  }
  std::size_t first = last;
  while (first > 0 && std::isdigit(static_cast<unsigned char>(stem[first - 1])))
  {
    --first;
  }
  const std::string digits = stem.substr(first, last + 1 - first);
  const auto significant = digits.find_first_not_of('0');
  if (significant != std::string::npos && digits.size() - significant > 9)
  {
    return -1;
  }
  return std::stoi(digits);
}

/// The file numbers when they identify the frames (all present, increasing),
/// else the indices.
std::vector<int> idsOf(const std::vector<std::string>& names)
{
  std::vector<int> ids;
  for (const std::string& name : names)
  {
    const int number = numberInName(name);
    if (number < 0 || (!ids.empty() && number <= ids.back()))
    {
      ids.resize(names.size());
      for (std::size_t i = 0; i < ids.size(); ++i)
      {
        ids[i] = static_cast<int>(i);
      }
      return ids;
    }
    ids.push_back(number);
  }
  return ids;
}

} // namespace

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
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(path, ec))
    {
      if (entry.is_regular_file() && isImageFileName(entry.path().filename().string()))
      {
        names.push_back(entry.path().filename().string());
      }
    }
    if (names.empty())
    {
      throwFileError(
        path, "the folder holds no image files (.png, .jpg, .jpeg, .bmp, .tif, .tiff)");
    }
    std::sort(names.begin(), names.end(), naturalLess);
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
