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
 * transform sequence"); read also from PLUS's NRRD form (`.igs.nrrd`).
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

/// @brief The two header forms a tracked sequence comes in.
enum class SequenceFileFormat
{
  /// MetaImage (`.mha`, `.mhd`): `Name = value` lines up to ElementDataFile.
  MetaImage,
  /// NRRD (`.nrrd`, `.nhdr`; PLUS's `.igs.nrrd`, Slicer's `.seq.nrrd`): a
  /// `NRRD000n` line, `field: value` and `key:=value` lines, `#` comments,
  /// and a blank line before the data.
  Nrrd
};

/**
 * @brief The header of a sequence metafile (the transforms' and, in Video's
 * TrackedSequenceFile.h, the frames' reader): its own fields, the fields of
 * each frame (`Seq_Frame0003_Timestamp` is frame 3's "Timestamp"), and
 * where its data begin.
 *
 * A NRRD whose frames have no Timestamp but whose sequence axis has numeric
 * index values (Slicer's `axis 3 index values:=0.04 0.08 ...`, in seconds)
 * has those values as its frames' Timestamps.
 */
struct SequenceMetafileHeader
{
  SequenceFileFormat format = SequenceFileFormat::MetaImage;
  /// The header's own fields by name (a NRRD's fields and keys alike).
  std::map<std::string, std::string> fields;
  std::map<long, std::map<std::string, std::string>> frames;
  /// True when the header ended where the data begin (an ElementDataFile
  /// line, a NRRD's blank line); local data begin at `dataOffset`.
  bool complete = false;
  std::streamoff dataOffset = 0;

  /**
   * @brief Frame `frame`'s Timestamp, s; empty when it has none.
   * @throws vimlop::Error "'path': frame 3's timestamp 'x' is not a number".
   */
  std::optional<double> timestampS(long frame, const std::string& path) const;
};

/**
 * @brief Reads the header of a sequence metafile (MetaImage or NRRD, told by
 * its first line) from `in` up to where its data begin (or the end of `in`),
 * so that binary data after it are never read as text.
 * @throws vimlop::Error "'path': line N ..." for a line that is not
 * `name = value` (NRRD: `field: value` or `key:=value`) or a frame field
 * without a frame number, a header over 64 MiB, or a NRRD sequence index
 * that is not a time in seconds.
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
