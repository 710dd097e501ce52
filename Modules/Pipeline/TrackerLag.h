#ifndef vimlop_TrackerLag_h
#define vimlop_TrackerLag_h

#include <vimlop/Pipeline/TrackerPrior.h>

#include <Eigen/Core>

#include <deque>
#include <optional>

namespace vimlop
{

class TrackerTrajectory;
struct TrackedFrame;

/// @brief Settings of TrackerLag (issue 16: the tracker's lag, learned from the video).
struct TrackerLagOptions
{
  /// The largest lag searched, either way, s (default 0.2; 0: the
  /// recording is read at the frames' times as given). Electromagnetic
  /// trackers report 10-100 ms late, and a clock offset adds to it; a lag
  /// beyond 0.2 s means the frames' times are wrong, which --time-offset
  /// sets.
  double maxLagS = 0.2;
  /// The search's step, s (default 0.005, a sixth of a frame at 30 Hz; the
  /// best step is refined between its neighbours).
  double stepS = 0.005;
  /// The lag is seen in the scope's displacement over about this long, s
  /// (default 1). A lag shows as the change of speed over the span times
  /// the lag, so the span must let the speed change by more than the
  /// tracker's noise over the lag (a 0.3 s span left a 60 ms lag 4-26 ms
  /// off in the unit test, 1 s within 2.5 ms); and it must be short enough
  /// that the video's drift does not show (millimetres over seconds where
  /// it is not anchored to the CT).
  double spanS = 1.0;
  /// Pairs of frames (neither lost) spanS apart needed for an estimate
  /// (default 60: two seconds of motion).
  int minPairs = 60;
  /// The estimate is made again after this many more such frames
  /// (default 30), over the last windowFrames of them (default 300), so a
  /// lag that changes is followed.
  int everyFrames = 30;
  int windowFrames = 300;

  /// @throws vimlop::Error naming the first value out of range.
  void validate() const;
};

/// @brief What one estimate of the lag found.
struct TrackerLagEstimate
{
  /// The lag that fits best, s: the recording is read this much after the
  /// frame's time (positive: the tracker reports late).
  double lagS = 0.0;
  /// Root mean square of the tracker's displacement over spanS minus the
  /// video's (over the pairs kept), at that lag and at none, mm.
  double disagreementMm = 0.0;
  double disagreementAtZeroMm = 0.0;
  /// Pairs of frames it was estimated from.
  int pairs = 0;
};

/**
 * @brief An electromagnetic tracker read at each frame's time plus the lag
 * the video has measured (issue 16).
 *
 * A tracker reports where the sensor was a little earlier (its latency), and
 * its clock is not the video's; the frames' time offset (--time-offset)
 * corrects what is known of both. What is left shows whenever the scope
 * moves: the tracker trails the video by its motion over the lag, which a
 * running offset (TrackerOffset) cannot take off since it changes with the
 * motion, and which a quick move turns into millimetres.
 *
 * The lag is found from the scope's displacements, not its positions: over
 * a second the video's pose moves as the scope does even where it is not
 * anchored to the CT (its features cast into a model that
 * is not the anatomy drift over seconds, and the clinical world anchors
 * almost no frame), while its position may be millimetres off. For each
 * pair of frames spanS apart (neither lost), the tracker's displacement
 * between the two times plus a lag is set against the video's; the lag is
 * the one whose disagreement is least, over a grid within maxLagS, refined
 * by a parabola through the least and its neighbours. The disagreement is
 * the mean square over the best 80 % of the pairs: a pose recast from the
 * tracker, a relocalisation or a wrong stretch makes a jump no lag
 * explains. A scope that keeps still, or moves at one speed, shows no lag
 * (a late tracker is then only shifted, which the offset takes off): the
 * estimate is kept only when the least lies inside the grid and the
 * disagreement at both ends of the grid is at least twice it, else the lag
 * stays as it was. While the tracker pulls unanchored poses towards the
 * sensor (EndoscopeTrackerOptions::trackerPull), the video carries a
 * tenth of the sensor's motion, and of its lag, in each frame.
 */
class TrackerLag
{
public:
  /// `recording` must outlive this; `trackerToCT` maps its positions into the CT.
  /// @throws vimlop::Error for invalid options.
  TrackerLag(const TrackerTrajectory& recording, const Eigen::Matrix4d& trackerToCT,
    const TrackerLagOptions& options);

  /// @brief What the tracker says of the camera at the frame's time
  /// `frameTimeS` (on the tracker's clock) plus the lag (trackerPriorAt()).
  std::optional<TrackerPrior> priorAt(double frameTimeS) const;

  /// @brief Takes in a frame as it was finally judged: its pose at
  /// `frameTimeS` joins the window unless the frame is lost; every
  /// everyFrames of them, the lag is estimated again.
  void learn(double frameTimeS, const TrackedFrame& frame);

  /// @brief The lag applied, s (0 until an estimate is kept).
  double lagS() const { return this->Lag; }
  /// @brief The last estimate kept, if any.
  const std::optional<TrackerLagEstimate>& estimate() const { return this->Last; }

  /**
   * @brief The lag that best fits `centresCT` (video camera centres, CT,
   * at `timesS`, in time order) to `recording`, searched as the class says;
   * none when the fit shows no lag (see the class), or fewer than minPairs
   * pairs of frames lie far enough inside the recording.
   */
  static std::optional<TrackerLagEstimate> fit(const TrackerTrajectory& recording,
    const Eigen::Matrix4d& trackerToCT, const std::deque<double>& timesS,
    const std::deque<Eigen::Vector3d>& centresCT, const TrackerLagOptions& options);

private:
  const TrackerTrajectory& Recording;
  Eigen::Matrix4d ToCT;
  TrackerLagOptions Options;
  std::deque<double> Times;
  std::deque<Eigen::Vector3d> Centres;
  int SinceEstimate = 0;
  double Lag = 0.0;
  std::optional<TrackerLagEstimate> Last;
};

} // namespace vimlop

#endif
