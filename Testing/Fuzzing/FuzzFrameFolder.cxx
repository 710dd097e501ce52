// Fuzzes the loading of a frame folder: the image headers read before any
// decoding (PNG, JPEG, BMP sizes against the frame and memory limits), then
// OpenCV's decoders. The first byte picks the two frames' formats (bits 0-1
// and 2-3: .png, .jpg, .bmp, .tif); the rest holds up to two files
// separated by "=====" lines. Seeds: small frames of each format and the
// frame folders of the bad-input corpus.
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Video/FrameSequence.h>

#include <opencv2/core/utils/logger.hpp>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 1)
  {
    return 0;
  }
  using namespace vimlop::fuzzing;
  static const char* const suffixes[] = { ".png", ".jpg", ".bmp", ".tif" };
  const std::string folder = emptyFolder("frames");
  const std::vector<std::string_view> parts = splitParts(data + 1, size - 1, 2);
  for (std::size_t i = 0; i < parts.size(); ++i)
  {
    if (!parts[i].empty())
    {
      writeFile(
        folder + "/frame" + std::to_string(i) + suffixes[(data[0] >> (2 * i)) & 3], parts[i]);
    }
  }
  try
  {
    vimlop::FrameSequence::load(folder);
  }
  catch (const vimlop::Error&)
  {
    // Rejecting bad input with a message is the expected outcome.
  }
  return 0;
}
