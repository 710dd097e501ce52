#include <vimlop/Video/FrameStream.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Video/FrameSequence.h>

#include "FrameFiles.h"
#include "VideoFileDecoder.h"

#include <opencv2/videoio.hpp>

#include <algorithm>
#include <climits>
#include <filesystem>

namespace vimlop
{

namespace
{

enum class Source
{
  Folder,
  VideoFile,
  Sequence,
  Camera
};

} // namespace

struct FrameStream::Internals
{
  Source kind = Source::Folder;
  std::string source;
  int next = 0;
  cv::Size size;
  // A folder: its image files and their ids.
  std::vector<std::string> names;
  std::vector<int> ids;
  // A video file, a tracked sequence (held whole), a camera.
  std::unique_ptr<detail::VideoFileDecoder> decoder;
  FrameSequence sequence;
  cv::VideoCapture camera;
  int device = 0;
};

FrameStream::FrameStream(std::unique_ptr<Internals> internals)
  : d(std::move(internals))
{
}

FrameStream::FrameStream(FrameStream&&) noexcept = default;
FrameStream& FrameStream::operator=(FrameStream&&) noexcept = default;
FrameStream::~FrameStream() = default;

FrameStream FrameStream::open(const std::string& path)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec))
  {
    throwFileError(path, "no such file or folder");
  }
  auto d = std::make_unique<Internals>();
  d->source = path;
  if (fs::is_directory(path, ec))
  {
    d->names = detail::imageFileNamesIn(path);
    d->ids = detail::idsOf(d->names);
  }
  else if (FrameSequence::isTrackedSequenceName(path))
  {
    d->kind = Source::Sequence;
    d->sequence = FrameSequence::load(path);
  }
  else
  {
    d->kind = Source::VideoFile;
    d->decoder =
      std::make_unique<detail::VideoFileDecoder>(path, INT_MAX, detail::videoDecoderProgram(),
        [path](int index, std::uint64_t width, std::uint64_t height)
        {
          std::uint64_t bytes = 0; // one frame at a time: only its own size counts
          detail::checkFrameSize(path, "frame" + std::to_string(index), width, height, 0, bytes);
        });
  }
  return FrameStream(std::move(d));
}

FrameStream FrameStream::openCamera(int device)
{
  const std::string node = "/dev/video" + std::to_string(device);
  auto d = std::make_unique<Internals>();
  d->kind = Source::Camera;
  d->device = device;
  d->source = "camera " + std::to_string(device) + " (" + node + ")";
  // Asked first, so that OpenCV does not print its own warnings for a
  // device that is not there.
  std::error_code ec;
  if (device < 0 || !std::filesystem::exists(node, ec))
  {
    throw Error(d->source + ": no such camera device on this machine");
  }
  if (!d->camera.open(device, cv::CAP_V4L2) || !d->camera.isOpened())
  {
    throw Error(d->source + ": cannot be opened (busy, or not a video capture device)");
  }
  return FrameStream(std::move(d));
}

bool FrameStream::next(StreamedFrame& frame)
{
  Internals& s = *this->d;
  // A frame that fails is passed all the same: a caller may go on after it.
  const int index = s.next++;
  frame.index = index;
  frame.id = index;
  frame.name = "frame" + std::to_string(index);
  frame.timestampS.reset();
  switch (s.kind)
  {
    case Source::Folder:
    {
      if (index >= static_cast<int>(s.names.size()))
      {
        s.next = index;
        return false;
      }
      frame.name = s.names[static_cast<std::size_t>(index)];
      frame.id = s.ids[static_cast<std::size_t>(index)];
      const cv::Mat image =
        detail::decodeImage((std::filesystem::path(s.source) / frame.name).string());
      std::uint64_t bytes = 0;
      detail::checkFrameSize(s.source, frame.name, static_cast<std::uint64_t>(image.cols),
        static_cast<std::uint64_t>(image.rows), 0, bytes);
      frame.image = detail::toBGR8(image);
      break;
    }
    case Source::VideoFile:
      frame.image = s.decoder->next();
      if (frame.image.empty())
      {
        s.next = index;
        return false;
      }
      break;
    case Source::Sequence:
      if (index >= s.sequence.size())
      {
        s.next = index;
        return false;
      }
      frame.image = s.sequence.frame(index);
      frame.name = s.sequence.name(index);
      frame.id = s.sequence.ids()[static_cast<std::size_t>(index)];
      frame.timestampS = s.sequence.timestampsS().empty()
        ? std::nullopt
        : std::optional<double>(s.sequence.timestampsS()[static_cast<std::size_t>(index)]);
      break;
    case Source::Camera:
      if (!s.camera.read(frame.image) || frame.image.empty())
      {
        throw Error(s.source + ": gave no frame " + std::to_string(index) +
          " (unplugged, or taken by another program)");
      }
      frame.image = detail::toBGR8(frame.image);
      break;
  }
  if (s.size.empty())
  {
    s.size = frame.image.size();
  }
  else if (frame.image.size() != s.size)
  {
    throwFileError(s.source,
      "frame '" + frame.name + "' is " + std::to_string(frame.image.cols) + "x" +
        std::to_string(frame.image.rows) + " but the first frame is " +
        std::to_string(s.size.width) + "x" + std::to_string(s.size.height));
  }
  return true;
}

std::optional<int> FrameStream::indexOfName(const std::string& name) const
{
  const Internals& s = *this->d;
  if (s.kind == Source::Folder)
  {
    const auto at = std::find(s.names.begin(), s.names.end(), name);
    return at == s.names.end() ? std::nullopt
                               : std::optional<int>(static_cast<int>(at - s.names.begin()));
  }
  if (s.kind == Source::Sequence)
  {
    for (int i = 0; i < s.sequence.size(); ++i)
    {
      if (s.sequence.name(i) == name)
      {
        return i;
      }
    }
    return std::nullopt;
  }
  if (s.kind == Source::VideoFile && name.rfind("frame", 0) == 0 && name.size() > 5 &&
    name.find_first_not_of("0123456789", 5) == std::string::npos && name.size() < 15)
  {
    return std::stoi(name.substr(5));
  }
  return std::nullopt;
}

const std::string& FrameStream::source() const
{
  return this->d->source;
}

} // namespace vimlop
