#ifndef vimlop_TrackerOffset_h
#define vimlop_TrackerOffset_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Pipeline/TrackerPrior.h>

#include <Eigen/Core>

namespace vimlop
{

/**
 * @brief What the video has taught of an electromagnetic tracker's error:
 * the offset from the tracker's pose to the video's, learned in frames
 * whose video pose is trusted (anchored to the CT), so that the tracker can
 * stand in for the video where it is not (issue 16).
 *
 * A navigation system's tracker is off by its registration to the patient
 * (about 1 mm) and by its sensor's calibration to the camera; both change
 * slowly. The offset is a shift in the CT frame and, for a 6-DOF sensor, a
 * turn in the CT frame (video rotation = turn x tracker rotation), each a
 * running mean over the last `memoryFrames` frames learned (exponentially
 * weighted; the first frames equally), so that the tracker's per-sample
 * noise averages out and a slowly changing error is followed.
 *
 * The mean is shrunk towards no error as if `priorFrames` frames had seen
 * none (the posterior mean under a prior of no error): n frames learned
 * apply n / (n + priorFrames) of it. A few frames do not make an error: a
 * tracker that lags the video shows, during a fast move, an offset that is
 * its motion over the lag (the clinical world of evaluate tracking learned
 * 2.2 mm and 4.0 degrees from three frames before a fast move, against a
 * sensor registered exactly).
 */
class TrackerOffset
{
public:
  /// @throws vimlop::Error for a memory below 1 frame or negative prior frames.
  explicit TrackerOffset(int memoryFrames, int priorFrames = 0);

  /// @brief Learns from one frame whose video pose `videoCT` is trusted and
  /// whose tracker said `prior`.
  void learn(const CameraPose& videoCT, const TrackerPrior& prior);

  /// @brief `prior` with the (shrunk) offset applied: where the tracker
  /// says the camera is once its learned error is taken off (as it is
  /// before anything was learned).
  TrackerPrior corrected(const TrackerPrior& prior) const;

  /// @brief Whether at least priorFrames frames (at least 1) have measured
  /// the tracker's position, and its rotation: then the video has checked
  /// it as much as the prior assumes.
  bool positionChecked() const;
  bool rotationChecked() const;

  /// @brief Forgets what was learned.
  void clear();

  /// Frames learned from since the last clear().
  int framesLearned() const { return this->Learned; }
  /// The shift applied, mm, CT frame (video centre minus the tracker's tip).
  Eigen::Vector3d shiftMm() const;
  /// The angle of the turn applied, degrees (0 for a position-only tracker).
  double turnDeg() const;

private:
  /// The shrunk turn, as a rotation vector (radians).
  Eigen::Vector3d turnVector() const;

  int Memory = 1;
  int PriorFrames = 0;
  int Learned = 0;
  int LearnedTurns = 0;
  Eigen::Vector3d Shift = Eigen::Vector3d::Zero();
  Eigen::Matrix3d Turn = Eigen::Matrix3d::Identity();
};

} // namespace vimlop

#endif
