#ifndef vimlop_VideoTracking_h
#define vimlop_VideoTracking_h

#include <vimlop/Core/Statistics.h>
#include <vimlop/Pipeline/ContourRelocalisation.h>
#include <vimlop/Pipeline/ContourWindowRefinement.h>
#include <vimlop/Pipeline/EndoscopeTracker.h>
#include <vimlop/Pipeline/TrackerLag.h>

#include <nlohmann/json.hpp>

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vimlop
{

struct TrackingStart;

/// @brief What VideoTracking reads and where it writes (`vimlop track`'s files).
struct VideoTrackingInputs
{
  /// The result folder of `vimlop register`: tracking starts on its last
  /// registered frame, with its model and camera.
  std::string resultFolder;
  /// The frames, read one at a time as they come: a folder of pictures, a
  /// video file or a tracked sequence. Exactly one of this and cameraIndex.
  std::string framesPath;
  /// A V4L2 camera, /dev/video<N> (-1, the default: none).
  int cameraIndex = -1;
  /// The intrinsics file given to `register`: the frames are undistorted
  /// with its lens (empty: they are used as they are).
  std::string intrinsicsPath;
  /// True camera poses (FramePose JSON): each frame's error is reported
  /// (empty: none).
  std::string truthPath;
  /// The electromagnetic tracker's recording of the scope's tip: a CSV
  /// (time_s, x_mm, y_mm, z_mm), or a tracked sequence with
  /// `trackerTransform` (readTrackerRecording()); empty: none. Its tip at
  /// each frame's time plus the lag measured (TrackerLag) is the tracker's
  /// prior (EndoscopeTracker::track()).
  std::string trackerPath;
  /// The transform of a tracked sequence that carries the scope (e.g.
  /// "ProbeToTracker"), read from `trackerPath`, or from the frames when
  /// they are that sequence and `trackerPath` is empty.
  std::string trackerTransform;
  /// The tracker registered to the patient (3D Slicer's tracker-to-RAS
  /// transform, an ITK transform file): needed with a tracker, whose
  /// positions are in its own frame.
  std::string trackerToCTPath;
  /// The time of the frames' first frame on the tracker's clock, s; frame
  /// id i is at timeOffsetS + (i - the first id) / videoFps.
  double timeOffsetS = 0.0;
  /// Where the outputs go (tracked-poses.json and .vtt, tracking.json,
  /// tracked-video.avi); empty: nothing is written.
  std::string outputFolder;
};

/// @brief Settings of VideoTracking; those of the tracker itself are in `tracker`.
struct VideoTrackingOptions
{
  EndoscopeTrackerOptions tracker;
  /// How the electromagnetic tracker's lag is measured from the video's
  /// motion (its frames not lost) and taken off its readings (TrackerLag).
  TrackerLagOptions trackerLag;
  /// Index of the first frame to track; -1 (default): the one after the
  /// registered frame of the same name, else 0.
  int firstFrameIndex = -1;
  /// Track from a result the registration flagged as a failure (default
  /// off: refused, since every tracked pose would carry its error).
  bool allowFlagged = false;
  /// Write tracked-video.avi (default on): each frame with the model's
  /// contours at its tracked pose, under a band with its state.
  bool writeVideo = true;
  /// The frames' rate, frames per second (default 30): the tracked video's,
  /// and the frame times on the electromagnetic tracker's clock.
  double videoFps = 30.0;
  /// Check every tracked pose against the CT (default on): the frame's
  /// occluding contours matched to the model's at the pose
  /// (FrameContourCheck), before the pose is handed on, so that a pose the
  /// contours disagree with is sent Degraded (TrackingSupervisor).
  bool checkContours = true;
  /// With the check: correct the tracker with the contours of its last
  /// frames (ContourWindowRefinement), the drift's remedy (default on).
  bool refineAgainstCT = true;
  ContourWindowRefinementOptions refinement;
  /// With the check: relocalise against the CT when the tracker lost its
  /// anchor (relocaliseAgainstCT(); default on). `relocalisation` also holds
  /// the contour error above which a frame is Degraded, searched or not.
  bool relocalise = true;
  ContourRelocalisationOptions relocalisation;

  /// @throws vimlop::Error naming the first value out of range.
  void validate() const;
};

/// @brief One frame as VideoTracking tracked it.
struct TrackedVideoFrame
{
  int frameId = 0;    ///< the frame's id in its source (its number, or its index)
  std::string source; ///< the frame's name (file, or video frame)
  TrackedFrame tracked;
  /// From the decoded frame to its pose, ms: undistortion, tracking and the
  /// frame handler (e.g. sending it to navigation software).
  double latencyMs = 0.0;
  /// FrameContourAgreement::medianErrorPx of the frame at its pose, px (NaN
  /// when not checked or when no contour point matched).
  double contourErrorPx = std::numeric_limits<double>::quiet_NaN();
  /// Contour points detected in the frame, and matched to the model's.
  int contourPointsDetected = 0;
  int contourPointsMatched = 0;
  /// How far the refinement or the relocalisation against the CT moved the
  /// camera after this frame, for the frames that follow, mm (0: not moved).
  double correctionMm = 0.0;
  /// Whether a relocalisation was searched after this frame, and whether
  /// it moved the tracker.
  bool searched = false;
  bool relocalised = false;
  /// The check against the CT (inside the latency) and what follows it
  /// (the refinement or the relocalisation, after), ms: a live camera's
  /// next frame waits for them.
  double checkMs = 0.0;
  /// Against the truth, when given.
  std::optional<double> positionErrorMm;
  std::optional<double> angleErrorDeg;
};

/**
 * @brief `vimlop track` as a library (issue 16): the endoscope followed
 * frame by frame after a registration, from a result folder and a stream of
 * frames to a pose in the CT for every frame, with its state. The command
 * line, vtkVIMLOPVideoTracking and Python's `vimlop.track_video` call it
 * with one set of defaults (VideoTrackingOptions).
 *
 * open() reads the start (TrackingStart: the result's last registered frame,
 * its pose, the model, the field stop), refuses a flagged result, opens the
 * frames and starts the EndoscopeTracker; run() tracks every frame after the
 * registered one, calls the frame handler with each pose as soon as it is
 * computed, and writes the outputs. A frame that cannot be read mid-way, or
 * a stop request, ends the run after the frames before it, which are
 * written all the same (stoppedBy(), stopRequested()).
 */
class VideoTracking
{
public:
  explicit VideoTracking(const VideoTrackingOptions& options = {});
  ~VideoTracking();
  VideoTracking(const VideoTracking&) = delete;
  VideoTracking& operator=(const VideoTracking&) = delete;

  /// @brief Called with each tracked frame, inside its latency (a live
  /// server sends the pose from here).
  void setFrameHandler(std::function<void(const TrackedVideoFrame&)> handler);
  /// @brief Asked before each frame: true stops the run after the frame in
  /// hand (Ctrl-C, AbortExecute), and the frames tracked are written.
  void setStopRequest(std::function<bool()> stopRequested);

  /**
   * @brief Reads the start and opens the frames.
   * @throws vimlop::Error for invalid options, not exactly one of framesPath
   * and cameraIndex, a result that cannot start tracking (unreadable, no
   * model, no picture of its last frame), a flagged result without
   * allowFlagged, intrinsics of another camera than the result's, frames
   * that cannot be opened, or a truth file that cannot be read.
   */
  void open(const VideoTrackingInputs& inputs);

  /**
   * @brief Tracks the frames until they end or a stop is requested, then
   * writes the outputs (when the inputs name a folder).
   * @throws vimlop::Error before open(), when a frame is of another size than
   * the result's camera, when there is no frame to track, when the first
   * frame cannot be read, or when an output cannot be written. A frame that
   * cannot be read later ends the run without throwing: see stoppedBy().
   */
  void run();

  /// @brief The start, after open().
  const TrackingStart& start() const;
  /// @brief The frames' source, e.g. the folder, file or camera device.
  const std::string& source() const;
  /// @brief Index of the first frame tracked, after open().
  int firstFrameIndex() const;
  /// @brief The frames tracked by run(), in order.
  const std::vector<TrackedVideoFrame>& frames() const;
  /// @brief How many frames run() tracked in `state`.
  int count(TrackingState state) const;
  /// @brief The frames' latency, ms.
  Summary latencyMs() const;
  /// @brief The error that ended the run early; empty when the frames ended
  /// or a stop was requested.
  const std::string& stoppedBy() const;
  /// @brief Whether the run ended on a stop request.
  bool stopRequested() const;
  /// @brief tracking.json: the counts, latency, errors and every frame.
  nlohmann::json report() const;

private:
  struct Internals;
  std::unique_ptr<Internals> d;
};

} // namespace vimlop

#endif
