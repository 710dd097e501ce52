#ifndef vimlop_TrackingProtocol_h
#define vimlop_TrackingProtocol_h

#include <vimlop/Core/Statistics.h>
#include <vimlop/Evaluation/EvaluationProgress.h>
#include <vimlop/Evaluation/VideoProtocol.h>
#include <vimlop/Pipeline/ContourRelocalisation.h>
#include <vimlop/Pipeline/ContourWindowRefinement.h>
#include <vimlop/Pipeline/EndoscopeTracker.h>
#include <vimlop/Pipeline/TrackerLag.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vimlop
{

struct SimulatedWorld;

/// @brief Settings of the tracking protocol (issue 16).
struct TrackingProtocolOptions
{
  /// The sequence: 600 frames by default, played forward and back along a
  /// path of 48 poses (24 mm at the path's 0.5 mm step: about the longest
  /// straight stretch of the bundled CT's airway with room to look ahead),
  /// with pauses and fast moves after a straight lead-in over the frames
  /// registered (EndoscopeSimulationOptions::replay); seed, camera, the
  /// world's error sources.
  EndoscopeSimulationOptions simulation = defaultSimulation();
  /// Frames registered by the main job before tracking starts (default 30,
  /// the paper's sequence), from P2's start; their settings and start are
  /// `registration`'s (its own `simulation` is ignored).
  int registrationFrames = 30;
  VideoProtocolOptions registration;
  /// The tracker.
  EndoscopeTrackerOptions tracker;
  /// Refine the tracked poses against the CT (ContourWindowRefinement), as
  /// vimlop track does, and with these settings.
  bool refineAgainstCT = true;
  ContourWindowRefinementOptions refinement;
  /// Relocalise against the CT when the last frames are suspect, as vimlop
  /// track does, and with these settings (which also set the contour error
  /// above which a frame is Degraded).
  bool relocalise = true;
  ContourRelocalisationOptions relocalisation;
  /// Give the tracker the simulated electromagnetic tracker's tip at each
  /// frame's time (EndoscopeTracker::track()'s prior; default off). The
  /// simulation records it in the CT frame, with trackerNoiseMm per axis
  /// and the simulation's latency and clock offset: a perfect navigation
  /// registration of the tracker to the CT. With the simulation's
  /// trackerRotation, the tracker's rotation too (a 6-DOF sensor).
  bool trackerPrior = false;
  /// With the prior: how the tracker's lag is measured and taken off, as
  /// vimlop track does (TrackerLag).
  TrackerLagOptions trackerLag;
  /// A frame farther than this from the truth is a failure the tracker must
  /// flag (degraded or lost), mm (default 2, issue 16).
  double flagErrorMm = 2.0;
  /// Frames at each end of the tracked stretch whose mean errors give the
  /// drift (default 60).
  int driftFrames = 60;

  /// @brief The default sequence (see `simulation`).
  static EndoscopeSimulationOptions defaultSimulation();

  /// @throws vimlop::Error naming the first invalid setting.
  void validate() const;
};

/// @brief One tracked frame of the protocol, against the truth.
struct TrackingProtocolFrame
{
  int frame = 0; ///< index in the sequence
  std::string state;
  double positionErrorMm = 0.0;
  double angleErrorDeg = 0.0;
  int trackedFeatures = 0;
  int inliers = 0;
  double reprojectionErrorPx = 0.0;
  double latencyMs = 0.0;
  /// FrameContourAgreement::medianErrorPx at the tracked pose (NaN when no
  /// contour point matched): the check against the CT, next to the truth.
  double contourErrorPx = 0.0;
  /// How far the refinement or the relocalisation against the CT moved the
  /// camera after this frame, mm (0: not).
  double correctionMm = 0.0;
  /// Whether a relocalisation was searched after this frame, found a pose,
  /// and how long it took, ms.
  bool searched = false;
  bool relocalised = false;
  double searchMs = 0.0;
};

/// @brief The result of the tracking protocol.
struct TrackingProtocolReport
{
  int frames = 0;
  std::uint64_t seed = 0;
  /// The registration the tracker starts from: frames, camera position error
  /// (mean, mm) over them, and the frame tracking starts on.
  int registrationFrames = 0;
  double registrationErrorMm = 0.0;
  double registrationSeconds = 0.0;
  /// Why the main job's failure flag (V13) would flag that registration;
  /// empty when it would not. The tracker starts from it either way.
  std::string registrationFailure;
  /// That registration's contour error (mean over its matched contour
  /// points, px): the refinement corrects only windows above it.
  double registrationContourErrorPx = 0.0;
  int startFrame = 0;
  /// Whether the tracker had the simulated electromagnetic tracker's tip
  /// (TrackingProtocolOptions::trackerPrior), and its rotation.
  bool trackerPrior = false;
  bool trackerRotation = false;
  /// The tracker's error as the tracker learned it at the end (frames
  /// learned from, the shift's length in mm, the turn in degrees;
  /// EndoscopeTracker::trackerOffset()), to set beside the simulated one.
  int trackerOffsetFramesLearned = 0;
  double trackerOffsetShiftMm = 0.0;
  double trackerOffsetTurnDeg = 0.0;
  /// The lag the video measured at the end, s, and the pairs of frames of
  /// that estimate (0 pairs: none was made, or none showed a lag), to set
  /// beside the simulation's latency and clock offset.
  double trackerLagS = 0.0;
  int trackerLagPairs = 0;
  /// Over the tracked frames (all after the start frame).
  Summary latencyMs;
  Summary positionErrorMm;
  Summary angleErrorDeg;
  /// Mean position error of the last `driftFrames` tracked frames minus that
  /// of the first, mm.
  double driftMm = 0.0;
  /// Frames not lost, over the tracked frames.
  double trackedFraction = 0.0;
  int degradedFrames = 0;
  int lostFrames = 0;
  /// Frames after which the refinement against the CT corrected the tracker.
  int correctedFrames = 0;
  /// Relocalisations searched, and those that found a pose.
  int relocalisationsSearched = 0;
  int relocalisationsFound = 0;
  /// Frames farther than flagErrorMm from the truth and reported tracking.
  int unflaggedFramesOverLimit = 0;
  double flagErrorMm = 0.0;
  std::vector<TrackingProtocolFrame> perFrame;

  /// @brief The report as `vimlop evaluate tracking` writes it.
  nlohmann::json toJson() const;
  /// @brief The lines `vimlop evaluate tracking` prints.
  std::vector<std::string> summaryLines() const;
};

/**
 * @brief Runs the tracking protocol in `world`: simulates the long sequence
 * from the world's truth, registers its first `registrationFrames` frames with
 * the main job (as P2 does, on the sequence's user files), starts the tracker
 * on the last registered frame at its registered pose, tracks every later
 * frame against the world's model and scores each against the truth. Needs
 * an X display.
 * The tracker is given the intrinsics a user has (calibratedIntrinsics, with
 * the lens and the calibration error of the world) and undistorts the frames
 * with them, as the registration does.
 * @throws vimlop::Error for invalid options or when a stage fails.
 */
TrackingProtocolReport runTrackingProtocol(const SimulatedWorld& world,
  const TrackingProtocolOptions& options, const EvaluationProgress& progress);

} // namespace vimlop

#endif
