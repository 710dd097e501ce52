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
 */
class TrackerOffset
{
public:
  /// @throws vimlop::Error for a memory below 1 frame.
  explicit TrackerOffset(int memoryFrames);

  /// @brief Learns from one frame whose video pose `videoCT` is trusted and
  /// whose tracker said `prior`.
  void learn(const CameraPose& videoCT, const TrackerPrior& prior);

  /// @brief `prior` with the offset applied: where the tracker says the
  /// camera is once its learned error is taken off (as it is before
  /// anything was learned).
  TrackerPrior corrected(const TrackerPrior& prior) const;

  /// @brief Forgets what was learned.
  void clear();

  /// Frames learned from since the last clear(), and of those the ones
  /// with a rotation (a 6-DOF sensor's): the turn is known only after one.
  int framesLearned() const { return this->Learned; }
  int turnsLearned() const { return this->LearnedTurns; }
  /// The learned shift, mm, CT frame (video centre minus the tracker's tip).
  const Eigen::Vector3d& shiftMm() const { return this->Shift; }
  /// The learned turn's angle, degrees (0 for a position-only tracker).
  double turnDeg() const;

private:
  int Memory = 1;
  int Learned = 0;
  int LearnedTurns = 0;
  Eigen::Vector3d Shift = Eigen::Vector3d::Zero();
  Eigen::Matrix3d Turn = Eigen::Matrix3d::Identity();
};

} // namespace vimlop

#endif
