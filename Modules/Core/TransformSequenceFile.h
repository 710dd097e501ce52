#ifndef vimlop_TransformSequenceFile_h
#define vimlop_TransformSequenceFile_h

#include <Eigen/Core>

#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

/**
 * @file TransformSequenceFile.h
 * @brief A sequence of one named linear transform over time, in the sequence
 * metafile form of PLUS and 3D Slicer (`.seq.mha`, Slicer's "linear
 * transform sequence").
 *
 * The file is a MetaImage header with no voxels (`DimSize = 0 0 N`) whose
 * per-item fields carry the transforms:
 * @code
 * Seq_Frame0000_CameraToCTTransform = r00 r01 r02 t0 r10 ... 0 0 0 1
 * Seq_Frame0000_CameraToCTTransformStatus = OK
 * Seq_Frame0000_Timestamp = 0.04
 * @endcode
 * The 16 numbers are the 4 x 4 matrix row by row; Slicer takes it as the
 * transform "to parent", as it is (no LPS/RAS change), and the timestamps
 * (s) as the sequence's index, rounded to the millisecond.
 */

namespace vimlop
{

/// @brief One item of a transform sequence: a 4 x 4 matrix at a time, s.
struct TimedTransform
{
  double timeS = 0.0;
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
};

/**
 * @brief The header of a sequence metafile (the transforms' and, in Video's
 * TrackedSequenceFile.h, the frames' reader): its own fields, the fields of
 * each frame (`Seq_Frame0003_Timestamp` is frame 3's "Timestamp"), and
 * where its data begin.
 */
struct SequenceMetafileHeader
{
  std::map<std::string, std::string> fields;
  std::map<long, std::map<std::string, std::string>> frames;
  /// True when an ElementDataFile line ended the header; its data (if
  /// LOCAL) begin at `dataOffset` in the stream.
  bool complete = false;
  std::streamoff dataOffset = 0;

  /**
   * @brief Frame `frame`'s Timestamp, s; empty when it has none.
   * @throws vimlop::Error "'path': frame 3's timestamp 'x' is not a number".
   */
  std::optional<double> timestampS(long frame, const std::string& path) const;
};

/**
 * @brief Reads the header of a sequence metafile from `in` up to its
 * ElementDataFile line (or the end of `in`), so that binary data after it
 * are never read as text.
 * @throws vimlop::Error "'path': line N ..." for a line that is not
 * `name = value` or a frame field without a frame number, or a header over
 * 64 MiB.
 */
SequenceMetafileHeader readSequenceMetafileHeader(std::istream& in, const std::string& path);

/**
 * @brief Writes the items as the sequence of the transform `name` (letters
 * and digits, e.g. "CameraToCT"), atomically, numbers written so that they
 * read back exactly.
 * @throws vimlop::Error for an empty sequence, a name that is not letters
 * and digits, times that do not increase by at least 1 ms (Slicer's index
 * would merge them) or are not finite, a matrix that is not finite, or a
 * file that cannot be written.
 */
void writeTransformSequenceFile(
  const std::vector<TimedTransform>& items, const std::string& name, const std::string& path);

/**
 * @brief Reads the sequence of the transform `name` from a sequence metafile
 * (written above, by Slicer or by PLUS), items in frame order; frames whose
 * status is not OK are left out.
 * @throws vimlop::Error naming the file: missing, not a sequence metafile (no
 * ObjectType), no item of that transform, a matrix that is not 16 numbers, a
 * frame without a timestamp, or as readSequenceMetafileHeader().
 */
std::vector<TimedTransform> readTransformSequenceFile(
  const std::string& path, const std::string& name);

} // namespace vimlop

#endif
