#ifndef vimlop_EndoscopeTrackerOptions_h
#define vimlop_EndoscopeTrackerOptions_h

#include <vimlop/Video/KltFeatureTracker.h>

namespace vimlop
{

/// @brief Settings of EndoscopeTracker (issue 16), each with its reason.
struct EndoscopeTrackerOptions
{
  /// Features tracked at most (default 300): PnP's accuracy grows slowly
  /// past a few hundred points, its cost linearly.
  int maxFeatures = 300;
  /// New corners are detected when fewer features than this are left
  /// (default 150), up to maxFeatures.
  int redetectBelow = 150;
  /// A feature agrees with a pose when it projects within this distance of
  /// where it was tracked, px (default 2: KLT's error on endoscope texture is
  /// well under a pixel, the model's error near a pixel).
  double inlierThresholdPx = 2.0;
  /// Fewer agreeing features than this and the frame is Lost (default 25).
  int minInliers = 25;
  /// A pose whose agreeing features are fewer than this fraction of those
  /// tracked is Degraded (default 0.6).
  double degradedInlierFraction = 0.6;
  /// A pose farther than this from the prediction is not believed (Lost),
  /// mm (default 5: the scope moves at most a few mm between frames at 30 Hz).
  double maxJumpMm = 5.0;
  /// Nor one turned by more than this from the prediction, degrees (default
  /// 10: a hand turns a scope by a few degrees between frames at 30 Hz).
  double maxTurnDeg = 10.0;
  /// Frames lost in a row over which the prediction goes on at the last
  /// speed (default 5, a sixth of a second at 30 Hz); after them it holds
  /// the last pose: a scope lost for longer has more likely stopped or
  /// turned than kept its speed.
  int maxCoastFrames = 5;
  /// New features stand for the model surface point their ray hits, at
  /// most this far from the camera, mm (default 60).
  double maxDepthMm = 60.0;
  /// New features whose ray meets the wall at a grazing angle (the cosine
  /// between the ray and the wall's normal below this, default 0.2) are
  /// dropped: near an occluding contour the point a pixel stands for jumps
  /// between the near and the far wall.
  double minIncidenceCosine = 0.2;
  /// Frames wider than this, px, are tracked halved (again and again until
  /// they fit; default 480): the pixel settings here and in `features` were
  /// chosen on 320 x 240 frames. Tracked as they were, 640 x 480 frames lost
  /// 14 of 299 frames (0.78 mm mean against 0.23 mm at 320 x 240) and
  /// 1280 x 960 frames 143, at 55 ms a frame (VIMLOPBenchmarkTracking, seed
  /// 1, ideal world). Poses are those of the full frames' camera either way.
  int maxTrackingWidthPx = 480;
  /// A pose whose optical centre lies farther than this from the
  /// electromagnetic tracker's tip (track()'s prior, its learned error
  /// taken off: trackerOffsetFrames), mm, is Degraded
  /// (default 3: clinical sinus navigation is off by 0.9 mm on average, so
  /// a larger disagreement means the video's pose, or the tracker's
  /// registration, is wrong).
  double maxTipDistanceMm = 3.0;
  /// A pose turned by more than this from a 6-DOF tracker's rotation
  /// (TrackerPrior::rotationCT), degrees, is Degraded (default 5: a 6-DOF
  /// sensor's orientation is good to a few tenths of a degree, its
  /// calibration to the camera to a degree or two, so a larger disagreement
  /// means a wrong pose or a slipped sensor).
  double maxTrackerTurnDeg = 5.0;
  /// After this many poses in a row that disagree with a 6-DOF tracker
  /// (beyond maxTipDistanceMm or maxTrackerTurnDeg), the features are cast
  /// again from the tracker's pose, at which that frame is reported
  /// (Degraded); 0: never (default 5, a sixth of a second at 30 Hz: the
  /// features then stand for a wrong world, which they would follow on).
  int recastFromTrackerAfterFrames = 5;
  /// The electromagnetic tracker's error is learned from the frames whose
  /// pose is Tracking (anchored to the CT, its features agreeing), over
  /// about this many frames (TrackerOffset), and taken off every prior
  /// before it is used; 0: the tracker is taken as it reads (default 90,
  /// 3 s at 30 Hz: long enough to average its noise, short enough to follow
  /// an error that changes as the scope moves through the field).
  int trackerOffsetFrames = 90;
  /// The learned error is shrunk towards none as if this many frames had
  /// seen none, and a pose is pulled towards the tracker (trackerPull) only
  /// once this many frames have measured it (default 30, 1 s at 30 Hz: a
  /// tracker that lags the video shows an offset during a fast move, which
  /// a few frames would take for its error; TrackerOffset).
  int trackerOffsetPriorFrames = 30;
  /// While not anchored, each pose found is moved this fraction of the way
  /// to the tracker's corrected pose, and its features' model points are
  /// cast again from there, so that the video gives the motion between
  /// frames and the tracker where the scope is; 0: never (default 0.1,
  /// which averages the tracker's noise over about 10 frames). Only in what
  /// the anchored video has measured of the tracker's error (its position,
  /// and its rotation, each once trackerOffsetPriorFrames frames have
  /// measured it): a tracker never checked against the CT would pull the
  /// pose into agreeing with it, and that agreement is what confirms a pose
  /// after a long loss (TrackingSupervisor).
  double trackerPull = 0.1;
  /// Frame-to-frame tracking and corner detection.
  KltFeatureTrackerOptions features;

  /// @throws vimlop::Error naming the first value out of range.
  void validate() const;
};

} // namespace vimlop

#endif
