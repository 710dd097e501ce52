#include <vimlop/Core/PathReplay.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>

namespace vimlop
{

void PathReplayOptions::validate() const
{
  if (this->isOff())
  {
    return;
  }
  if (this->pathFrames < 2)
  {
    throw Error(
      formatText("path replay: the path needs at least 2 poses, not %d", this->pathFrames));
  }
  if (!(this->pauseShare >= 0.0 && this->fastShare >= 0.0 &&
        this->pauseShare + this->fastShare <= 1.0))
  {
    throw Error(formatText("path replay: the shares of pauses (%g) and fast moves (%g) must not be "
                           "negative nor add up to more than 1",
      this->pauseShare, this->fastShare));
  }
  if (!(this->fastSpeed >= 1.0 && this->fastSpeed <= 20.0))
  {
    throw Error(
      formatText("path replay: the fast speed must lie in [1, 20] path steps per frame, not %g",
        this->fastSpeed));
  }
  if (this->leadFrames < 0 || this->leadFrames > this->pathFrames - 1)
  {
    throw Error(formatText("path replay: %d lead frames do not fit a path of %d poses",
      this->leadFrames, this->pathFrames));
  }
  if (this->minSegmentFrames < 1 || this->maxSegmentFrames < this->minSegmentFrames)
  {
    throw Error(formatText("path replay: segments of %d to %d frames are not a range",
      this->minSegmentFrames, this->maxSegmentFrames));
  }
}

std::vector<double> replayPositions(
  int frames, const PathReplayOptions& options, std::uint64_t seed)
{
  options.validate();
  if (options.isOff())
  {
    throw Error("path replay: no path length given");
  }
  if (frames < 1)
  {
    throw Error(formatText("path replay: at least 1 frame, not %d", frames));
  }
  std::mt19937_64 generator(seed);
  // Uniform in [0, 1) from the raw output, the same on every platform.
  auto uniform = [&] { return static_cast<double>(generator() >> 11) * 0x1.0p-53; };
  const double end = options.pathFrames - 1;
  std::vector<double> positions;
  positions.reserve(static_cast<std::size_t>(frames));
  double at = 0.0;
  double direction = 1.0; // the first move goes into the passage
  for (int i = 0; i < options.leadFrames && static_cast<int>(positions.size()) < frames; ++i)
  {
    positions.push_back(at);
    at += 1.0;
  }
  while (static_cast<int>(positions.size()) < frames)
  {
    const int span = options.minSegmentFrames +
      static_cast<int>(uniform() * (options.maxSegmentFrames - options.minSegmentFrames + 1));
    const double kind = uniform();
    const double speed = kind < options.pauseShare    ? 0.0
      : kind < options.pauseShare + options.fastShare ? options.fastSpeed
                                                      : 1.0;
    if (!positions.empty() && uniform() < 0.5)
    {
      direction = -direction;
    }
    for (int i = 0; i < span && static_cast<int>(positions.size()) < frames; ++i)
    {
      positions.push_back(at);
      at += direction * speed;
      // Back at either end, reflected.
      if (at > end)
      {
        at = std::max(0.0, 2.0 * end - at);
        direction = -direction;
      }
      else if (at < 0.0)
      {
        at = std::min(end, -at);
        direction = -direction;
      }
    }
  }
  return positions;
}

std::vector<CameraPose> replayPath(const std::vector<CameraPose>& path, int frames,
  const PathReplayOptions& options, std::uint64_t seed)
{
  if (static_cast<int>(path.size()) != options.pathFrames)
  {
    throw Error(formatText(
      "path replay: a path of %zu poses, but %d were asked for", path.size(), options.pathFrames));
  }
  std::vector<CameraPose> poses;
  for (double at : replayPositions(frames, options, seed))
  {
    const std::size_t i = std::min(static_cast<std::size_t>(at), path.size() - 2);
    const double t = at - static_cast<double>(i);
    const CameraPose& a = path[i];
    const CameraPose& b = path[i + 1];
    CameraPose pose;
    pose.centre = (1.0 - t) * a.centre + t * b.centre;
    pose.rotation = Eigen::Quaterniond(a.rotation)
                      .slerp(t, Eigen::Quaterniond(b.rotation))
                      .normalized()
                      .toRotationMatrix();
    poses.push_back(pose);
  }
  return poses;
}

} // namespace vimlop
