#ifndef vimlop_PathReplay_h
#define vimlop_PathReplay_h

#include <vimlop/Core/CameraPose.h>

#include <cstdint>
#include <vector>

namespace vimlop
{

/**
 * @brief How a long sequence is played along a short path (issue 16): the
 * scope goes forward and back through the same stretch of airway, stands
 * still, and moves fast, as a surgeon's does.
 *
 * The sequence is cut into segments of `minSegmentFrames` to
 * `maxSegmentFrames` frames, each with one speed along the path, in steps of
 * the path per frame: standing still (0) with probability `pauseShare`, fast
 * (`fastSpeed`) with probability `fastShare`, otherwise 1; forward or back
 * with equal chance. The scope turns back at either end of the path. Drawn
 * from the caller's seed (a 64-bit Mersenne Twister's raw output, the same
 * on every platform).
 */
struct PathReplayOptions
{
  /// Poses of the path played (default 0: no replay, the path is the
  /// sequence). At least 2 when on.
  int pathFrames = 0;
  /// Share of the segments spent standing still (default 0.15).
  double pauseShare = 0.15;
  /// Share of the segments moved fast (default 0.15).
  double fastShare = 0.15;
  /// Speed of a fast segment, path steps per frame (default 3: 1.5 mm per
  /// frame with the path's 0.5 mm step, 45 mm/s at 30 fps).
  double fastSpeed = 3.0;
  /// Length of a segment, frames (defaults 15 and 60: half a second to two
  /// seconds at 30 fps).
  int minSegmentFrames = 15;
  int maxSegmentFrames = 60;
  /// The first frames go straight into the passage at speed 1 before any
  /// pause or turn (default 0): a registration of those frames needs the
  /// parallax of a steady advance. At most pathFrames - 1.
  int leadFrames = 0;

  /// @brief True when the sequence is the path itself.
  bool isOff() const { return pathFrames == 0; }

  /// @throws vimlop::Error naming the first value out of range.
  void validate() const;
};

/**
 * @brief Where each of `frames` frames stands on a path of
 * `options.pathFrames` poses: a position in [0, pathFrames - 1], frame 0 at 0.
 * @throws vimlop::Error for invalid options or fewer than 1 frame.
 */
std::vector<double> replayPositions(
  int frames, const PathReplayOptions& options, std::uint64_t seed);

/**
 * @brief The poses of `frames` frames played along `path` (replayPositions()
 * of its length): centres interpolated linearly between neighbouring poses,
 * rotations spherically.
 * @throws vimlop::Error as replayPositions(), or when `path` has another
 * length than `options.pathFrames`.
 */
std::vector<CameraPose> replayPath(const std::vector<CameraPose>& path, int frames,
  const PathReplayOptions& options, std::uint64_t seed);

} // namespace vimlop

#endif
