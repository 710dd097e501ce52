#ifndef vimlop_VideoInput_h
#define vimlop_VideoInput_h

#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Video/FrameSequence.h>
#include <vimlop/Video/SfmReconstruction.h>
#include <vimlop/Video/TrackerScale.h>
#include <vimlop/Video/TrackerTrajectory.h>

#include <opencv2/core/mat.hpp>

#include <iosfwd>
#include <string>
#include <vector>

/**
 * @file VideoInput.h
 * @brief The video stages `vimlop sfm` and `vimlop register` share: frames
 * checked against the intrinsics and undistorted, SfM (built in or a COLMAP
 * model), frame times and the tracker scale (V14).
 */
namespace vimlop
{

/**
 * @brief The frames as an ideal pinhole camera sees them: undistorted with
 * the intrinsics' coefficients (a note on `log` when they are not zero),
 * in their lens model: cv::undistort, or for the fisheye
 * cv::fisheye::initUndistortRectifyMap and cv::remap; either keeps K, so
 * that the undistorted frames are the pinhole camera of the same fx, fy,
 * cx, cy (black where the lens saw nothing).
 * @throws vimlop::Error when the intrinsics are not for the frames' size.
 */
std::vector<cv::Mat> idealFrames(const FrameSequence& sequence, const PinholeCamera& intrinsics,
  const std::string& framesPath, const std::string& intrinsicsPath, std::ostream* log);

/**
 * @brief Structure from motion of the frames: VIMLOP's own when
 * `colmapFolder` is empty, else the COLMAP sparse model in that folder
 * (frames matched by name). Warnings and unregistered frames go to `log`.
 * VIMLOP's own SfM detects features only on the non-zero pixels of
 * `featureMask` when it is not empty (a COLMAP model is read as it is), on
 * `threads` threads (0: the hardware concurrency; the result is the same).
 */
SfmReconstruction reconstructFrames(const std::vector<cv::Mat>& frames,
  const std::vector<std::string>& names, const PinholeCamera& ideal,
  const std::string& colmapFolder, int threads, std::ostream* log,
  const cv::Mat& featureMask = cv::Mat());

/// @brief Time of frame `frameId` on the tracker's clock: offset + (id -
/// first id) / fps, so that the first frame is at the offset and a missing
/// frame (a gap in FrameSequence::ids()) is a gap in time.
double frameTimeS(int frameId, int firstFrameId, double fps, double offsetS);

/// @brief frameTimeS() of each frame, the first id being the first.
std::vector<double> frameTimesS(const std::vector<int>& frameIds, double fps, double offsetS);

/// @brief The frame rate assumed when neither the frames nor the user give one.
constexpr double defaultFramesPerSecond = 30.0;

/**
 * @brief The rate the frames were taken at, frames per second: `fps` (the
 * user's) when it is positive, else `recordedFps` (the file's,
 * FrameSequence::framesPerSecond()) when it is, else defaultFramesPerSecond.
 */
double framesPerSecondOf(double recordedFps, double fps);

/**
 * @brief Time of each frame on the tracker's clock, from what the frames'
 * file records and what the user gives. `timestampsS`
 * (FrameSequence::timestampsS(), one per id, or empty) are the frames' own
 * times: with `fps` 0 they are used, plus `offsetS`. Frames without them are
 * at offset + (id - first id) / rate, the rate framesPerSecondOf(): `fps`,
 * else `recordedFps` (the video's), else 30 fps, which `warning` then says.
 * A positive `fps` overrides the file's rate (the first frame keeps its
 * timestamp), with a warning when they disagree by more than 1 %.
 * @throws vimlop::Error for a negative or non-finite `fps`.
 */
std::vector<double> frameTimesS(const std::vector<int>& frameIds,
  const std::vector<double>& timestampsS, double recordedFps, double fps, double offsetS,
  std::string* warning);

/**
 * @brief The initial scale (SfM units to mm) from the tracked trajectory over
 * the registered frames; warnings go to `log`.
 * @throws vimlop::Error when the tracker and the frames do not overlap.
 */
TrackerScaleResult scaleFromTracker(const TrackerTrajectory& tracker, const SfmReconstruction& sfm,
  const std::vector<double>& timesS, std::ostream* log);

} // namespace vimlop

#endif
