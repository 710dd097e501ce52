#ifndef vimlop_ContourRelocalisation_h
#define vimlop_ContourRelocalisation_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/ContourPoint.h>
#include <vimlop/Core/SimilarityTransform.h>

#include <optional>
#include <vector>

namespace vimlop
{

class FrameContourCheck;

/// @brief Settings of the tracker's check and relocalisation against the CT
/// (issue 16), each with its reason.
struct ContourRelocalisationOptions
{
  /// A tracked frame whose contours lie farther than this from the model's
  /// (FrameContourAgreement::medianErrorPx) is not trusted: it is reported
  /// Degraded, px (default 6). In the ideal world the frames within 1 mm of
  /// the truth lie at 1.3-3.6 px (90th percentile over a 600-frame run, seeds
  /// 1-5), and those over 2 mm at 16-29 px (seed 4).
  double degradedAbovePx = 6.0;
  /// Nor one whose contours lie farther than this many times the
  /// registration's own contour error (default 4): where the model is not
  /// the anatomy the contours disagree with it by that much at the truth.
  double degradedAboveRegistered = 4.0;
  /// The registration's contour error, px (TrackingStart::contourErrorPx; 0
  /// when unknown).
  double registeredErrorPx = 0.0;
  /// Frames whose contours are registered together when relocalising: the
  /// last ones since the last lost frame (default 1). After a loss the
  /// tracker's relative poses come from features cast from a prediction,
  /// which bends them: three such frames of the rendered tube fit the model
  /// no better than 3.1 px, where the last frame alone found its pose within
  /// 0.3 mm.
  int windowFrames = 1;
  /// Relocalise when this many frames in a row were tracked from features
  /// cast from a prediction (default 3; lost frames between them are not
  /// counted), and the last one's contours lie above degradedLimitPx().
  /// Frames only their contours distrust are not searched for, nor frames
  /// whose contours are within that limit: on `evaluate tracking`'s seed 4
  /// (ideal world), searching such frames moved poses 0.3-0.5 mm off to
  /// 1.7-2.9 mm and 5.6-9 degrees off, where one frame's contours fit
  /// within 0.6 px.
  int triggerFrames = 3;
  /// Frames after an attempt before the next (default 15, half a second at
  /// 30 Hz): a search costs several frames' time.
  int retryFrames = 15;
  /// The search starts from the tracked pose and from it moved by this much
  /// along each of the camera's axes, and turned by searchDeg about each of
  /// them (defaults 2 mm and 5 degrees: the errors of a tracker that has
  /// drifted; a correction farther than twice these is refused).
  double searchMm = 2.0;
  double searchDeg = 5.0;
  /// Match-and-update rounds from each start (default 15): one frame's
  /// contours pull slowly along a shift with a turn. After a loss on the
  /// rendered tube, 6 rounds left a frame 1.6 mm off at 3.3 px at best; 15
  /// reached 0.8 px and 0.4 mm.
  int iterations = 15;
  /// A search succeeds when the window's contours lie within this of the
  /// model's at the pose it finds, px (default 2: in the ideal world the
  /// frames within 0.25 mm of the truth lie at 1.3 px and those 0.25-0.5 mm
  /// off at 2.2 px, medians on seed 3), or within acceptAboveRegistered
  /// times the registration's error (default 1.5) when that is larger.
  double acceptPx = 2.0;
  double acceptAboveRegistered = 1.5;

  /// @brief The contour error above which a frame is not trusted, px.
  double degradedLimitPx() const;
  /// @brief The contour error a relocalisation must reach, px.
  double acceptLimitPx() const;

  /// @throws vimlop::Error naming the first value out of range.
  void validate() const;
};

/// @brief One frame of a relocalisation window: its detected contours and tracked pose.
struct RelocalisationFrame
{
  std::vector<ContourPoint> contours; ///< FrameContourCheck::detect()
  CameraPose cameraToCT;
};

/// @brief The outcome of relocaliseAgainstCT().
struct RelocalisationResult
{
  /// The smallest rigid move of the window's cameras that lays their
  /// contours within the accepted error of the model's; none when no start
  /// reached it.
  std::optional<SimilarityTransform> correction;
  /// The window's contour error at the tracked poses and the lowest found
  /// (the median over its frames of each frame's median), px.
  double trackedErrorPx = 0.0;
  double bestErrorPx = 0.0;
  int starts = 0; ///< starts searched
};

/**
 * @brief Relocalisation of the tracked cameras against the CT (issue 16):
 * a multi-start restricted to poses near the tracked one, each refined by
 * V-IMLOP on the window's contours alone (match at the pose, V3-V5; rigid
 * pose update, V6, scale 1; the anatomical constraint, V10). Of the poses
 * found that lay the window's contours within the accepted error, the
 * nearest to the tracked pose is kept: in a narrow passage a sideways
 * shift with a turn lays them almost as well as the truth (measured on
 * `evaluate tracking`: taking the lowest error moved good poses 1.7 mm and
 * 5.6 degrees off).
 *
 * The starts are the tracked pose and the 12 poses around it: moved by
 * searchMm along each axis of the last frame's camera (forward and back
 * along the airway, sideways), and turned by searchDeg about each. The
 * window's frames move together, keeping their poses relative to one
 * another (TrackingSupervisor passes one frame: after a loss the tracker's
 * relative poses are bent, see ContourRelocalisationOptions::windowFrames).
 *
 * @param window the frames, the last one the current (at least one)
 * @throws vimlop::Error for an empty window or invalid options.
 */
RelocalisationResult relocaliseAgainstCT(const FrameContourCheck& check,
  const std::vector<RelocalisationFrame>& window, const ContourRelocalisationOptions& options);

} // namespace vimlop

#endif
