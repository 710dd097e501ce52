#ifndef vimlop_FrameSequence_h
#define vimlop_FrameSequence_h

#include <opencv2/core/mat.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief The frames of an endoscopic video sequence, in memory, in order.
 *
 * Frames come from a folder of images (`.png`, `.jpg`, `.jpeg`, `.bmp`,
 * `.tif`, `.tiff`, sorted by name with digit runs compared as numbers, so
 * `frame2.png` comes before `frame10.png`) or from a video file, decoded by
 * FFmpeg's `ffmpeg` program in a child process (`$VIMLOP_FFMPEG` names another
 * program), so that a decoder's fault on a broken file ends that process with
 * a message, not this one, or from a tracked image sequence as PLUS and 3D
 * Slicer record it (`.igs.mha`, `.seq.mha`, `.mha`, `.mhd`: a MetaImage whose
 * third axis is time; `.igs.nrrd`, `.seq.nrrd`, `.nrrd`, `.nhdr`: a NRRD whose
 * last axis is the list of frames; with a timestamp per frame, or Slicer's
 * sequence index values in seconds; frames whose image status is not OK are
 * left out). All frames are 8-bit BGR and share one size. Sequences for
 * registration are short (about 30 frames), so they are held in memory.
 */
class FrameSequence
{
public:
  /**
   * @brief Loads at most `maxFrames` frames from a folder or a video file.
   * @throws vimlop::Error naming the path and the problem: missing, empty
   * folder, unreadable image or video, frames of different sizes, a frame
   * larger than MaxFramePixels or frames beyond MaxDecodedBytes (both judged
   * from the file headers of PNG, JPEG and BMP frames before decoding, and
   * from each video frame's header before its pixels are read), a video
   * decoder that is missing, fails, stops answering for 60 s or ends inside
   * a frame.
   */
  static FrameSequence load(const std::string& path, int maxFrames = 10000);

  int size() const { return static_cast<int>(this->Frames.size()); }
  bool empty() const { return this->Frames.empty(); }
  const cv::Mat& frame(int i) const { return this->Frames.at(static_cast<size_t>(i)); }
  /// @brief File name of frame i (folder input) or "frame<i>" (video input).
  const std::string& name(int i) const { return this->Names.at(static_cast<size_t>(i)); }
  /**
   * @brief The time of each frame (s) as its file records it (a tracked
   * sequence's timestamps, on the tracker's clock), in order; empty when the
   * file records none (folders and video files).
   */
  const std::vector<double>& timestampsS() const { return this->TimestampsS; }
  /**
   * @brief The rate the file records, frames per second: a video stream's
   * average frame rate (read by `ffprobe`), a tracked sequence's mean rate
   * over its timestamps (a frame left out counts); 0 when it records none
   * (a folder, or a video whose rate cannot be read).
   */
  double framesPerSecond() const { return this->FramesPerSecond; }
  /// @brief The names of all frames, in order.
  const std::vector<std::string>& names() const { return this->Names; }
  /**
   * @brief The id of each frame, in order: the number in its file name (the
   * last run of digits: `frame011.png` is 11) when every name of the folder
   * has one and they increase in the frames' order, so that a missing file is
   * a gap in the ids and not a shift of every later frame; otherwise, and for
   * a video file, the frame's index; for a tracked sequence, the frame's
   * number in the file (a frame left out is a gap).
   */
  const std::vector<int>& ids() const { return this->Ids; }
  /**
   * @brief "" when the ids run without a gap; otherwise what is missing, for
   * a warning: "frame 10 (between 'frame009.png' and 'frame011.png')".
   */
  std::string idGaps() const;
  int widthPx() const { return this->Frames.empty() ? 0 : this->Frames.front().cols; }
  int heightPx() const { return this->Frames.empty() ? 0 : this->Frames.front().rows; }

  /// @brief The largest frame load() decodes: 8192 x 8192 pixels (a 4K
  /// endoscope frame is 3840 x 2160); checked on the file's header first.
  static constexpr std::uint64_t MaxFramePixels = std::uint64_t(8192) * 8192;
  /// @brief The most memory the decoded frames of one sequence may take
  /// (8 GiB: 340 frames of 4K video; a registration uses about 30).
  static constexpr std::uint64_t MaxDecodedBytes = std::uint64_t(8) << 30;

  /// @brief True when the name looks like an image file this class reads.
  static bool isImageFileName(const std::string& name);

  /// @brief True when the name ends as a tracked sequence's (`.mha`, `.mhd`,
  /// `.nrrd`, `.nhdr`): a file of frames, and of the transforms a tracker is
  /// read from (TrackerTrajectory::readTrackedSequence()).
  static bool isTrackedSequenceName(const std::string& name);

private:
  std::vector<cv::Mat> Frames;
  std::vector<std::string> Names;
  std::vector<int> Ids;
  std::vector<double> TimestampsS;
  double FramesPerSecond = 0.0;
};

} // namespace vimlop

#endif
