#include "VideoFileDecoder.h"

#include <vimlop/Core/ChildProcess.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>

#include <opencv2/imgproc.hpp>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

namespace vimlop::detail
{

namespace
{

/// The last line the decoder wrote to stderr, for a message.
std::string lastLine(const std::string& text)
{
  std::size_t end = text.find_last_not_of(" \r\n\t");
  if (end == std::string::npos)
  {
    return std::string();
  }
  const std::size_t start = text.rfind('\n', end);
  return text.substr(start == std::string::npos ? 0 : start + 1,
    end + 1 - (start == std::string::npos ? 0 : start + 1));
}

/// " (ffmpeg: what it said last)", with how it ended when that was not by
/// itself; the file's own name is left out of its line.
std::string said(const std::string& program, const std::string& path, const ChildProcess& decoder,
  const ChildProcessResult* end = nullptr)
{
  std::string line = lastLine(decoder.errorOutput());
  const std::string input = "file:" + std::filesystem::absolute(path).string() + ": ";
  if (line.compare(0, input.size(), input) == 0)
  {
    line.erase(0, input.size());
  }
  std::string how;
  if (end != nullptr && end->signal != 0)
  {
    how = " was killed by signal " + std::to_string(end->signal);
  }
  else if (end != nullptr && line.empty())
  {
    how = " failed with exit code " + std::to_string(end->exitCode);
  }
  const std::string name = std::filesystem::path(program).filename().string();
  if (how.empty() && line.empty())
  {
    return std::string();
  }
  return " (" + name + how + (line.empty() ? "" : (how.empty() ? ": " : ", saying: ") + line) + ")";
}

/// The decoder's next `bytes` bytes (fewer at its end); a decoder silent for
/// `idleTimeoutS` is refused naming the video.
std::size_t readFrom(ChildProcess& decoder, const std::string& path, char* into, std::size_t bytes,
  double idleTimeoutS)
{
  try
  {
    return decoder.read(into, bytes, idleTimeoutS);
  }
  catch (const Error& e)
  {
    throwFileError(path, "the video decoder stopped answering: " + std::string(e.what()));
  }
}

std::string frameCount(std::size_t n)
{
  return std::to_string(n) + (n == 1 ? " frame" : " frames");
}

/// One number of a PPM header after its whitespace; `next` gets the byte after it.
std::uint64_t ppmNumber(
  ChildProcess& decoder, const std::string& path, double idleTimeoutS, char& next, bool& ok)
{
  char c = 0;
  do
  {
    if (readFrom(decoder, path, &c, 1, idleTimeoutS) != 1)
    {
      ok = false;
      return 0;
    }
  } while (c == ' ' || c == '\n' || c == '\r' || c == '\t');
  std::uint64_t value = 0;
  int digits = 0;
  while (std::isdigit(static_cast<unsigned char>(c)) && digits < 10)
  {
    value = value * 10 + static_cast<std::uint64_t>(c - '0');
    ++digits;
    if (readFrom(decoder, path, &c, 1, idleTimeoutS) != 1)
    {
      ok = false;
      return 0;
    }
  }
  ok = ok && digits > 0 && digits < 10;
  next = c;
  return value;
}

/// The next frame's header "P6 width height 255" and its one whitespace
/// byte: false when the output ended before it.
bool readPpmHeader(ChildProcess& decoder, const std::string& path, int frame, double idleTimeoutS,
  std::uint64_t& width, std::uint64_t& height)
{
  char magic[2] = {};
  const std::size_t got = readFrom(decoder, path, magic, 2, idleTimeoutS);
  if (got == 0)
  {
    return false;
  }
  bool ok = got == 2 && magic[0] == 'P' && magic[1] == '6';
  char after = 0;
  width = ok ? ppmNumber(decoder, path, idleTimeoutS, after, ok) : 0;
  height = ok ? ppmNumber(decoder, path, idleTimeoutS, after, ok) : 0;
  const std::uint64_t maxValue = ok ? ppmNumber(decoder, path, idleTimeoutS, after, ok) : 0;
  if (!ok || maxValue != 255 || !std::isspace(static_cast<unsigned char>(after)) || width == 0 ||
    height == 0)
  {
    throwFileError(path,
      "the video decoder's output is not an 8-bit PPM image at frame " + std::to_string(frame));
  }
  return true;
}

} // namespace

std::string videoDecoderProgram()
{
  const char* program = std::getenv("VIMLOP_FFMPEG");
  return program != nullptr && *program != '\0' ? program : "ffmpeg";
}

std::vector<std::string> videoDecoderArguments(
  const std::string& program, const std::string& path, int maxFrames)
{
  // "file:" and the protocol list keep a name like "http:..." or a playlist
  // inside the file from reaching anything but local files.
  return { program, "-nostdin", "-hide_banner", "-loglevel", "error", "-protocol_whitelist", "file",
    "-i", "file:" + std::filesystem::absolute(path).string(), "-map", "0:v:0", "-frames:v",
    std::to_string(maxFrames), "-fps_mode", "passthrough", "-f", "image2pipe", "-c:v", "ppm",
    "-pix_fmt", "rgb24", "pipe:1" };
}

double videoFramesPerSecond(const std::string& path)
{
  const char* given = std::getenv("VIMLOP_FFPROBE");
  const std::string program = given != nullptr && *given != '\0' ? given : "ffprobe";
  try
  {
    ChildProcess probe({ program, "-v", "error", "-protocol_whitelist", "file", "-select_streams",
      "v:0", "-show_entries", "stream=avg_frame_rate", "-of", "default=noprint_wrappers=1:nokey=1",
      "file:" + std::filesystem::absolute(path).string() });
    char text[64] = {};
    const std::size_t got = probe.read(text, sizeof(text) - 1, 10.0);
    probe.finish(true);
    // "25/1", "30000/1001"; "0/0" when the container has no rate.
    double numerator = 0.0;
    double denominator = 0.0;
    if (got > 0 && std::sscanf(text, "%lf/%lf", &numerator, &denominator) == 2 && numerator > 0.0 &&
      denominator > 0.0 && std::isfinite(numerator / denominator))
    {
      return numerator / denominator;
    }
  }
  catch (const Error&)
  {
  }
  return 0.0;
}

VideoFileDecoder::VideoFileDecoder(const std::string& path, int maxFrames,
  const std::string& program, std::function<void(int, std::uint64_t, std::uint64_t)> checkSize,
  double idleTimeoutS)
  : Path(path)
  , Program(program)
  , MaxFrames(maxFrames)
  , IdleTimeoutS(idleTimeoutS)
  , CheckSize(std::move(checkSize))
{
  try
  {
    this->Decoder = std::make_unique<ChildProcess>(videoDecoderArguments(program, path, maxFrames));
  }
  catch (const Error& e)
  {
    throwFileError(path,
      "a video file is decoded by FFmpeg's 'ffmpeg' program (Debian package 'ffmpeg', or "
      "$VIMLOP_FFMPEG), which cannot be run here: " +
        std::string(e.what()) + "; or give a folder of frame images");
  }
}

VideoFileDecoder::~VideoFileDecoder()
{
  if (this->Decoder && !this->Finished)
  {
    this->Decoder->finish(true);
  }
}

cv::Mat VideoFileDecoder::next()
{
  if (this->Finished)
  {
    return cv::Mat();
  }
  ChildProcess& decoder = *this->Decoder;
  const std::string& path = this->Path;
  std::uint64_t width = 0;
  std::uint64_t height = 0;
  if (this->Decoded < this->MaxFrames &&
    readPpmHeader(decoder, path, this->Decoded, this->IdleTimeoutS, width, height))
  {
    this->CheckSize(this->Decoded, width, height);
    cv::Mat rgb(static_cast<int>(height), static_cast<int>(width), CV_8UC3);
    const std::size_t bytes = rgb.total() * rgb.elemSize();
    const std::size_t got =
      readFrom(decoder, path, reinterpret_cast<char*>(rgb.data), bytes, this->IdleTimeoutS);
    if (got != bytes)
    {
      this->Finished = true;
      decoder.finish(true);
      throwFileError(path,
        "the video decoder stopped inside frame " + std::to_string(this->Decoded) + " (" +
          std::to_string(got) + " of its " + std::to_string(bytes) + " bytes)" +
          said(this->Program, path, decoder));
    }
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    ++this->Decoded;
    return bgr;
  }
  // A decoder with frames left is stopped; one that ended is judged by how.
  this->Finished = true;
  const bool enough = this->Decoded >= this->MaxFrames;
  const ChildProcessResult end = decoder.finish(enough);
  if (!enough && (end.exitCode != 0 || end.signal != 0))
  {
    throwFileError(path,
      (this->Decoded == 0 ? std::string("not a readable video file")
                          : "the video decoder failed after " +
            frameCount(static_cast<std::size_t>(this->Decoded))) +
        said(this->Program, path, decoder, &end));
  }
  if (this->Decoded == 0)
  {
    throwFileError(path, "the video has no readable frames" + said(this->Program, path, decoder));
  }
  return cv::Mat();
}

std::vector<cv::Mat> decodeVideoFile(const std::string& path, int maxFrames,
  const std::string& program,
  const std::function<void(int, std::uint64_t, std::uint64_t)>& checkSize, double idleTimeoutS)
{
  VideoFileDecoder decoder(path, maxFrames, program, checkSize, idleTimeoutS);
  std::vector<cv::Mat> frames;
  for (cv::Mat frame = decoder.next(); !frame.empty(); frame = decoder.next())
  {
    frames.push_back(frame);
  }
  return frames;
}

} // namespace vimlop::detail
