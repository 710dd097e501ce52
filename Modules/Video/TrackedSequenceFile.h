#ifndef vimlop_TrackedSequenceFile_h
#define vimlop_TrackedSequenceFile_h

// Private to the Video module (not installed): the frames of a tracked image
// sequence as PLUS and 3D Slicer record it, a MetaImage (`.igs.mha`,
// `.seq.mha`, `.mha`; `.mhd` with its data file) whose third axis is time, or
// a NRRD (PLUS's `.igs.nrrd`, Slicer's volume sequence `.seq.nrrd`; `.nhdr`
// with its data file) whose last axis is the list of frames.

#include <opencv2/core/mat.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vimlop::detail
{

/// @brief The frames of a tracked sequence whose image status is OK, in order.
struct TrackedSequenceFrames
{
  /// 8-bit BGR (grey and RGB frames are converted).
  std::vector<cv::Mat> frames;
  /// The frame's number in the file (`Seq_Frame<number>_...`): frames left
  /// out (status not OK) are gaps.
  std::vector<int> numbers;
  /// The frame's `Seq_Frame<number>_Timestamp`, s.
  std::vector<double> timestampsS;
};

/// @brief True when `path` is a file whose name ends with `.mha`, `.mhd`,
/// `.nrrd` or `.nhdr`.
bool isTrackedSequencePath(const std::string& path);

/**
 * @brief Reads at most `maxFrames` frames of a tracked sequence, rows as the
 * file stores them (PLUS's "MF" orientation: the image as the camera saw it).
 * `checkSize(index, widthPx, heightPx)` judges the frame size before any
 * pixel is read (it throws to refuse).
 * @throws vimlop::Error "'path': problem": not a 3-D MetaImage or a NRRD
 * of 2-D frames of 8-bit pixels with 1, 3 or 4 channels (NRRD: raw or gzip
 * encoded), a frame without a timestamp, timestamps that do not increase,
 * data shorter than the header promises or that does not inflate, no frame
 * whose status is OK.
 */
TrackedSequenceFrames readTrackedSequence(const std::string& path, int maxFrames,
  const std::function<void(int, std::uint64_t, std::uint64_t)>& checkSize);

} // namespace vimlop::detail

#endif
