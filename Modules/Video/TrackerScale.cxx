#include <vimlop/Video/TrackerScale.h>

#include <vimlop/Core/Error.h>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace vimlop
{

namespace
{

std::string timeSpans(const TrackerTrajectory& tracker, const std::vector<double>& frameTimesS)
{
  char span[160];
  std::snprintf(span, sizeof(span), "tracker %.3f..%.3f s, frames %.3f..%.3f s", tracker.startS(),
    tracker.endS(), frameTimesS.empty() ? 0.0 : frameTimesS.front(),
    frameTimesS.empty() ? 0.0 : frameTimesS.back());
  return span;
}

} // namespace

void checkTrackerOverlap(const TrackerTrajectory& tracker, const std::vector<double>& frameTimesS)
{
  for (double t : frameTimesS)
  {
    if (t >= tracker.startS() && t <= tracker.endS())
    {
      return;
    }
  }
  throw Error("tracker scale: the tracker and the frames do not overlap in time (" +
    timeSpans(tracker, frameTimesS) + ")");
}

TrackerScaleResult estimateTrackerScale(const TrackerTrajectory& tracker,
  const std::vector<double>& frameTimesS, const std::vector<Eigen::Vector3d>& sfmCentres,
  const TrackerScaleOptions& options)
{
  if (frameTimesS.size() != sfmCentres.size())
  {
    throw Error("tracker scale: " + std::to_string(frameTimesS.size()) + " frame times but " +
      std::to_string(sfmCentres.size()) + " camera centres");
  }
  TrackerScaleResult result;
  std::vector<Eigen::Vector3d> tracked;
  std::vector<Eigen::Vector3d> sfm;
  int outsideTime = 0;
  int unregistered = 0;
  for (size_t f = 0; f < frameTimesS.size(); ++f)
  {
    const int frame = static_cast<int>(f);
    if (!sfmCentres[f].allFinite())
    {
      ++unregistered;
      result.framesDropped.push_back(frame);
      continue;
    }
    const std::optional<Eigen::Vector3d> p = tracker.positionAt(frameTimesS[f], options.smoothingS);
    if (!p)
    {
      ++outsideTime;
      result.framesDropped.push_back(frame);
      continue;
    }
    result.framesUsed.push_back(frame);
    tracked.push_back(*p);
    sfm.push_back(sfmCentres[f]);
  }
  const std::string span = timeSpans(tracker, frameTimesS);
  checkTrackerOverlap(tracker, frameTimesS);
  if (static_cast<int>(tracked.size()) < options.minFrames)
  {
    throw Error("tracker scale: only " + std::to_string(tracked.size()) +
      " frame(s) have both a tracker position and an SfM camera; at least " +
      std::to_string(options.minFrames) + " needed (" + span + ")");
  }
  if (outsideTime > 0)
  {
    result.warnings.push_back("tracker scale: dropped " + std::to_string(outsideTime) +
      " frame(s) outside the tracker's time span (" + span + ")");
  }
  if (unregistered > 0)
  {
    result.warnings.push_back("tracker scale: dropped " + std::to_string(unregistered) +
      " frame(s) that SfM did not register");
  }
  // Chords between frames at least minChordMm apart on the tracker.
  size_t last = 0;
  for (size_t i = 1; i < tracked.size(); ++i)
  {
    const double chord = (tracked[i] - tracked[last]).norm();
    if (chord >= options.minChordMm || i + 1 == tracked.size())
    {
      result.trackerLengthMm += chord;
      result.sfmLength += (sfm[i] - sfm[last]).norm();
      last = i;
    }
  }
  if (!(result.trackerLengthMm > 0.0) || !(result.sfmLength > 0.0))
  {
    throw Error("tracker scale: the " +
      std::string(result.trackerLengthMm > 0.0 ? "SfM" : "tracked") +
      " trajectory has no length (the endoscope did not move)");
  }
  // A tracker in metres moves a thousandth of what it should: the scale
  // would be 1000 times too small, and every start outside the anatomy.
  if (result.trackerLengthMm < 1.0)
  {
    std::ostringstream text;
    text << "tracker scale: the tracked trajectory is only " << result.trackerLengthMm
         << " mm long over " << tracked.size()
         << " frames, too short for a scale: are the tracker's positions in metres? They are "
            "read as mm (or give the initial scale)";
    throw Error(text.str());
  }
  if (result.trackerLengthMm < 2.0 * options.minChordMm)
  {
    result.warnings.push_back("tracker scale: the tracked trajectory is only " +
      std::to_string(result.trackerLengthMm) + " mm long; the scale is uncertain");
  }
  result.scale = result.trackerLengthMm / result.sfmLength;
  return result;
}

} // namespace vimlop
