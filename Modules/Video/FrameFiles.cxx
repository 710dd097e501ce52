#include "FrameFiles.h"

#include <vimlop/Core/FileError.h>
#include <vimlop/Video/FrameSequence.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace vimlop::detail
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

std::vector<std::string> imageFileNamesIn(const std::string& folder)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec))
  {
    if (entry.is_regular_file() && FrameSequence::isImageFileName(entry.path().filename().string()))
    {
      names.push_back(entry.path().filename().string());
    }
  }
  if (names.empty())
  {
    throwFileError(
      folder, "the folder holds no image files (.png, .jpg, .jpeg, .bmp, .tif, .tiff)");
  }
  std::sort(names.begin(), names.end(), naturalLess);
  return names;
}

} // namespace vimlop::detail
