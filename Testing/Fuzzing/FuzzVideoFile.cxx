// Fuzzes the loading of a video file (OpenCV's FFmpeg back end behind
// FrameSequence::load): the container's frame size is judged before the
// first frame is decoded, the decoded frames against the memory limit. The
// first byte picks the container (.avi, .mp4, .mkv), the rest is the file.
// Seeds: short videos of small frames in each container.
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
  static const char* const suffixes[] = { ".avi", ".mp4", ".mkv" };
  const std::string path = vimlop::fuzzing::writeInput(data + 1, size - 1, suffixes[data[0] % 3]);
  try
  {
    // A registration uses about 30 frames; more only repeats the decoder.
    vimlop::FrameSequence::load(path, 8);
  }
  catch (const vimlop::Error&)
  {
    // Rejecting bad input with a message is the expected outcome.
  }
  return 0;
}
