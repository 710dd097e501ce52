#ifndef vimlop_FrameStream_h
#define vimlop_FrameStream_h

#include <opencv2/core/mat.hpp>

#include <memory>
#include <optional>
#include <string>

namespace vimlop
{

/// @brief One frame as a FrameStream delivers it.
struct StreamedFrame
{
  /// 8-bit BGR, the size of the stream's first frame.
  cv::Mat image;
  /// File name (folder), or "frame<index>" (video file, tracked sequence, camera).
  std::string name;
  /// The number in the file names when they identify the frames (as
  /// FrameSequence::ids()), else the index.
  int id = 0;
  /// Position in the stream, from 0.
  int index = 0;
  /// The time the source recorded for the frame, s (a tracked sequence's
  /// timestamp); none for a folder, a video file or a camera.
  std::optional<double> timestampS;
};

/**
 * @brief Endoscope frames one at a time, as they come: what a tracker
 * reads, where FrameSequence holds a short sequence in memory.
 *
 * The sources are FrameSequence's (a folder of images in natural order, a
 * video file decoded by `ffmpeg` in a child process, a tracked image
 * sequence, which is read whole) and a camera (a V4L2 device,
 * `/dev/video<N>`, through OpenCV). A frame that cannot be read ends the
 * stream with an error that names it; the frames delivered before it stay
 * good. Frames larger than FrameSequence::MaxFramePixels, or of another size
 * than the first, are refused.
 */
class FrameStream
{
public:
  /**
   * @brief A folder of frames, a video file or a tracked sequence.
   * @throws vimlop::Error naming the path: missing, a folder without images,
   * a video decoder that cannot be started.
   */
  static FrameStream open(const std::string& path);

  /**
   * @brief The camera `/dev/video<device>`.
   * @throws vimlop::Error when it does not exist or cannot be opened.
   */
  static FrameStream openCamera(int device);

  FrameStream(FrameStream&&) noexcept;
  FrameStream& operator=(FrameStream&&) noexcept;
  ~FrameStream();

  /**
   * @brief The next frame into `frame`; false after the last one.
   * @throws vimlop::Error naming the frame that cannot be read (an
   * unreadable image file, a video decoder that failed, a camera that
   * stopped, a frame of another size).
   */
  bool next(StreamedFrame& frame);

  /// @brief The index a frame called `name` has, when the stream can tell
  /// without reading: a folder's file names, a video's "frame<index>".
  std::optional<int> indexOfName(const std::string& name) const;

  /// @brief The path, or "camera <N> (/dev/video<N>)".
  const std::string& source() const;

private:
  struct Internals;
  explicit FrameStream(std::unique_ptr<Internals> d);
  std::unique_ptr<Internals> d;
};

} // namespace vimlop

#endif
