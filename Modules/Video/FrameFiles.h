#ifndef vimlop_FrameFiles_h
#define vimlop_FrameFiles_h

// Private to the Video module (not installed): how frames are read from
// image files, shared by FrameSequence (a whole sequence in memory) and
// FrameStream (one frame at a time).

#include <opencv2/core/mat.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vimlop::detail
{

/// @brief "frame2" < "frame10": digit runs compare by value, the rest by character.
bool naturalLess(const std::string& a, const std::string& b);

/// @brief The image file names of `folder` (FrameSequence::isImageFileName()), in natural order.
/// @throws vimlop::Error naming the folder when it holds none.
std::vector<std::string> imageFileNamesIn(const std::string& folder);

/// @brief One image file decoded as it is stored.
/// @throws vimlop::Error naming the file when it is not a readable image.
cv::Mat decodeImage(const std::string& file);

/// @brief An image as 8-bit BGR (16-bit scaled down, grey and BGRA converted).
cv::Mat toBGR8(const cv::Mat& image);

/**
 * @brief Refuses a frame of `width` x `height` pixels before it is decoded
 * when it is larger than any endoscope's (FrameSequence::MaxFramePixels),
 * or when it would take the sequence past FrameSequence::MaxDecodedBytes;
 * `decodedBytes` counts the frames so far.
 */
void checkFrameSize(const std::string& path, const std::string& name, std::uint64_t width,
  std::uint64_t height, int framesSoFar, std::uint64_t& decodedBytes);

/// @brief The last run of digits in a file name's stem ("frame011.png": 11),
/// or -1 when there is none or it does not fit an int.
int numberInName(const std::string& name);

/// @brief The file numbers when they identify the frames (all present,
/// increasing), else the indices.
std::vector<int> idsOf(const std::vector<std::string>& names);

} // namespace vimlop::detail

#endif
