#ifndef vimlop_VideoFileDecoder_h
#define vimlop_VideoFileDecoder_h

// Private to the Video module (not installed): the frames of a video file,
// decoded in a child process. A decoder's fault (OpenCV 4.6's FFmpeg
// wrapper overflowed a heap buffer on an 86-byte stream) ends that process
// with an error message, not this one; its frames arrive as binary PPM
// images on a pipe, each judged on its header before its pixels are read.

#include <opencv2/core/mat.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace vimlop
{
class ChildProcess;
}

namespace vimlop::detail
{

/// @brief The decoding program: $VIMLOP_FFMPEG when set, else "ffmpeg" on PATH.
std::string videoDecoderProgram();

/// @brief The decoder's arguments: the first `maxFrames` frames of the first
/// video stream of the file `path` (the file protocol only), every frame as
/// it is stored, as 8-bit RGB PPM images on its stdout.
std::vector<std::string> videoDecoderArguments(
  const std::string& program, const std::string& path, int maxFrames);

/**
 * @brief The average frame rate of the first video stream of `path`, frames
 * per second, as FFmpeg's `ffprobe` (beside `ffmpeg`; $VIMLOP_FFPROBE names
 * another) reads it from the container; 0 when it cannot tell (no ffprobe,
 * no rate in the file, an answer that is not a positive rate). Never throws:
 * the rate is a default, the decoder reports what is wrong with the file.
 */
double videoFramesPerSecond(const std::string& path);

/**
 * @brief The frames of a video file one at a time, as the decoder gives
 * them (what decodeVideoFile() does, for a consumer that must not wait for
 * the whole file: tracking). The decoder is stopped on destruction.
 */
class VideoFileDecoder
{
public:
  /// @brief Starts `program` on `path` (arguments and checks as decodeVideoFile()).
  VideoFileDecoder(const std::string& path, int maxFrames, const std::string& program,
    std::function<void(int, std::uint64_t, std::uint64_t)> checkSize, double idleTimeoutS = 60.0);
  ~VideoFileDecoder();
  VideoFileDecoder(const VideoFileDecoder&) = delete;
  VideoFileDecoder& operator=(const VideoFileDecoder&) = delete;

  /**
   * @brief The next frame (8-bit BGR); empty after the last one.
   * @throws vimlop::Error as decodeVideoFile() does, when the frame that
   * would come next cannot be: the frames returned before stay good.
   */
  cv::Mat next();

  /// @brief Frames returned so far.
  int decoded() const { return this->Decoded; }

private:
  std::string Path;
  std::string Program;
  int MaxFrames = 0;
  double IdleTimeoutS = 60.0;
  std::function<void(int, std::uint64_t, std::uint64_t)> CheckSize;
  std::unique_ptr<ChildProcess> Decoder;
  int Decoded = 0;
  bool Finished = false;
};

/**
 * @brief Decodes at most `maxFrames` frames of the video `path` with
 * `program` (ffmpeg's arguments, as above) into 8-bit BGR images.
 * `checkSize(index, widthPx, heightPx)` judges each frame from its header
 * before its pixels are read (it throws to refuse). The decoder is given
 * `idleTimeoutS` for each piece of output.
 * @throws vimlop::Error "'path': problem": no decoder, a decoder that fails
 * or is killed (with the last line it wrote), output that is not PPM frames
 * or ends inside one, no frame at all.
 */
std::vector<cv::Mat> decodeVideoFile(const std::string& path, int maxFrames,
  const std::string& program,
  const std::function<void(int, std::uint64_t, std::uint64_t)>& checkSize,
  double idleTimeoutS = 60.0);

} // namespace vimlop::detail

#endif
