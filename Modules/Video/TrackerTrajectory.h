#ifndef vimlop_TrackerTrajectory_h
#define vimlop_TrackerTrajectory_h

#include <Eigen/Core>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vimlop
{

/**
 * @brief Positions of the endoscope tip recorded by an electromagnetic
 * tracker, with timestamps (V14), and the sensor's rotations when it has
 * six degrees of freedom.
 *
 * Positions are in mm in the tracker's own frame (which need not be the CT
 * frame: the initial scale uses only lengths, tracking and the canonical
 * starts' rotation prior the tracker's registration to the CT); times in
 * seconds on the clock of the video frames. Samples are kept sorted by time
 * with distinct times.
 */
class TrackerTrajectory
{
public:
  /// @brief One tracker reading.
  struct Sample
  {
    Sample() = default;
    /// A reading; with a rotation when the recording has one (so that
    /// `{ t, position }` reads as a position-only sample).
    Sample(double t, const Eigen::Vector3d& position,
      std::optional<Eigen::Matrix3d> sensorRotation = std::nullopt)
      : timeS(t)
      , positionMm(position)
      , rotation(std::move(sensorRotation))
    {
    }

    double timeS = 0.0;
    Eigen::Vector3d positionMm = Eigen::Vector3d::Zero();
    /// The sensor's rotation into the tracker's frame, when the recording
    /// has it (a tracked sequence's transform; a CSV with `qw,qx,qy,qz`).
    std::optional<Eigen::Matrix3d> rotation;
  };

  TrackerTrajectory() = default;

  /**
   * @brief A trajectory from samples in any order; samples with the same time
   * as an earlier one are dropped, and so are glitches: samples farther from
   * the median of the 3 before and after them than a tip moving 100 mm/s
   * could be, plus 10 mm (each with a warning in `warnings`).
   * @throws vimlop::Error for fewer than 2 samples or a non-finite value.
   */
  explicit TrackerTrajectory(
    std::vector<Sample> samples, std::vector<std::string>* warnings = nullptr);

  /**
   * @brief Reads a CSV file: a header line naming the columns, then one
   * sample per line. The columns `time_s`, `x_mm`, `y_mm`, `z_mm` are
   * required (also accepted: `t`/`time`/`timestamp` and `x`/`y`/`z`). A
   * 6-DOF sensor's rotation (into the tracker's frame) is read from the
   * columns `qw`, `qx`, `qy`, `qz`, a unit quaternion, when the header has
   * them; any other column is ignored. Blank lines and lines starting with
   * `#` are skipped. Malformed rows (with rotation columns: also a row
   * without a quaternion, or with one whose length is not 1 within 0.01)
   * are dropped with a warning naming the line.
   * @throws vimlop::Error naming the file for a missing file, a missing
   * column, a header with some but not all of the rotation's columns, or
   * fewer than 2 usable rows.
   */
  static TrackerTrajectory readCsv(
    const std::string& path, std::vector<std::string>* warnings = nullptr);

  /**
   * @brief Reads the positions of the transform `transformName` (e.g.
   * "ProbeToTracker") of a tracked sequence file as PLUS and 3D Slicer write
   * it (`.igs.mha`, `.seq.mha`, `.igs.nrrd`: TransformSequenceFile.h): the origin of the
   * transform's frame, in mm in the tracker's frame, at each frame whose
   * transform status is OK, at the frame's timestamp.
   * @throws vimlop::Error as readTransformSequenceFile() does, or for fewer
   * than 2 usable samples.
   */
  static TrackerTrajectory readTrackedSequence(const std::string& path,
    const std::string& transformName, std::vector<std::string>* warnings = nullptr);
  /// @brief Writes the samples in the layout readCsv() reads, with the
  /// rotation's columns when every sample has a rotation.
  void writeCsv(const std::string& path) const;

  const std::vector<Sample>& samples() const { return this->Samples; }
  /// @brief Whether every sample has a rotation (a 6-DOF sensor's recording).
  bool hasRotations() const;
  double startS() const { return this->Samples.front().timeS; }
  double endS() const { return this->Samples.back().timeS; }

  /**
   * @brief Position at `timeS`: a line fitted to the samples around it with
   * Gaussian weights of standard deviation `smoothingS` in time (seconds),
   * which averages the tracker's noise without lagging at the ends; with
   * `smoothingS` 0, linear interpolation between the neighbouring samples.
   * Empty outside [startS(), endS()].
   */
  std::optional<Eigen::Vector3d> positionAt(double timeS, double smoothingS = 0.0) const;

  /**
   * @brief The sensor's pose (its frame to the tracker's, mm) at `timeS`:
   * position and rotation interpolated between the neighbouring samples
   * (linearly, and along the shorter arc). Empty outside [startS(), endS()]
   * or when those samples have no rotation.
   */
  std::optional<Eigen::Matrix4d> poseAt(double timeS) const;

private:
  std::vector<Sample> Samples;
};

} // namespace vimlop

#endif
