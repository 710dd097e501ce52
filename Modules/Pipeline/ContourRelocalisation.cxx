#include <vimlop/Pipeline/ContourRelocalisation.h>

#include <vimlop/Core/AnatomicalConstraint.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/PoseUpdate.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Core/VideoFrame.h>
#include <vimlop/Pipeline/FrameContourCheck.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vimlop
{

double ContourRelocalisationOptions::degradedLimitPx() const
{
  return std::max(this->degradedAbovePx, this->degradedAboveRegistered * this->registeredErrorPx);
}

double ContourRelocalisationOptions::acceptLimitPx() const
{
  return std::max(this->acceptPx, this->acceptAboveRegistered * this->registeredErrorPx);
}

void ContourRelocalisationOptions::validate() const
{
  auto refuse = [](const char* what, double value)
  { throw Error(formatText("relocalisation: %s, not %g", what, value)); };
  if (!(this->degradedAbovePx > 0.0) || !(this->degradedAboveRegistered > 0.0))
  {
    refuse("the contour error of an untrusted frame must be positive (px, times the "
           "registration's)",
      this->degradedAbovePx > 0.0 ? this->degradedAboveRegistered : this->degradedAbovePx);
  }
  if (!(this->registeredErrorPx >= 0.0))
  {
    refuse("the registration's contour error must not be negative (px)", this->registeredErrorPx);
  }
  if (this->windowFrames < 1)
  {
    refuse("the window needs at least 1 frame", this->windowFrames);
  }
  if (this->triggerFrames < 1)
  {
    refuse("at least 1 unanchored frame must trigger a search", this->triggerFrames);
  }
  if (this->retryFrames < 1)
  {
    refuse("at least 1 frame must pass between searches", this->retryFrames);
  }
  if (!(this->searchMm > 0.0) || !(this->searchDeg > 0.0))
  {
    refuse("the search must reach a positive distance and angle (mm, degrees)",
      this->searchMm > 0.0 ? this->searchDeg : this->searchMm);
  }
  if (this->iterations < 1)
  {
    refuse("each start needs at least 1 iteration", this->iterations);
  }
  if (!(this->acceptPx > 0.0) || !(this->acceptAboveRegistered > 0.0))
  {
    refuse("the accepted contour error must be positive (px, times the registration's)",
      this->acceptPx > 0.0 ? this->acceptAboveRegistered : this->acceptPx);
  }
}

namespace
{

/// Fewer matched contour points than this over the window and a pose is not
/// scored: too few to tell one pose from another.
constexpr int MinMatched = 30;
/// Halvings of an update that takes a camera out of the airway (V10).
constexpr int MaxBackoffSteps = 4;

/// The window's contour error with its cameras moved by `move`: the median
/// over its frames of each frame's median (NaN when too few points match),
/// and their pairs for the pose update (frame i of the window).
double windowError(const FrameContourCheck& check, const std::vector<RelocalisationFrame>& window,
  const SimilarityTransform& move, std::vector<ContourPair>* pairs)
{
  std::vector<double> perFrame;
  int matched = 0;
  for (std::size_t i = 0; i < window.size(); ++i)
  {
    const FrameContourAgreement a =
      check.agreement(window[i].contours, move.apply(window[i].cameraToCT));
    if (!std::isfinite(a.medianErrorPx))
    {
      continue;
    }
    perFrame.push_back(a.medianErrorPx);
    matched += a.matched;
    if (pairs)
    {
      for (ContourPair p : a.pairs)
      {
        p.frame = static_cast<int>(i);
        pairs->push_back(p);
      }
    }
  }
  if (matched < MinMatched)
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return summarize(std::move(perFrame)).median;
}

/// The rigid move that turns the camera at `pose` by `turn` (about its own
/// axes, through its centre), and shifts it by `shift` (its own axes, mm).
SimilarityTransform moveOfCamera(
  const CameraPose& pose, const Eigen::Vector3d& shift, const Eigen::AngleAxisd& turn)
{
  SimilarityTransform move;
  move.rotation = pose.rotation * turn.toRotationMatrix() * pose.rotation.transpose();
  move.translation = pose.centre + pose.rotation * shift - move.rotation * pose.centre;
  return move;
}

} // namespace

RelocalisationResult relocaliseAgainstCT(const FrameContourCheck& check,
  const std::vector<RelocalisationFrame>& window, const ContourRelocalisationOptions& options)
{
  options.validate();
  if (window.empty())
  {
    throw Error("relocalisation: no frames to relocalise");
  }
  const CameraPose& current = window.back().cameraToCT;
  std::vector<SimilarityTransform> starts{ SimilarityTransform() };
  const double angle = options.searchDeg * M_PI / 180.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (const double sign : { -1.0, 1.0 })
    {
      const Eigen::Vector3d unit = Eigen::Vector3d::Unit(axis);
      starts.push_back(
        moveOfCamera(current, sign * options.searchMm * unit, Eigen::AngleAxisd(0.0, unit)));
      starts.push_back(
        moveOfCamera(current, Eigen::Vector3d::Zero(), Eigen::AngleAxisd(sign * angle, unit)));
    }
  }
  // The window as a registration's data: its "SfM" frame is the CT at the
  // tracked poses, T the move of all its cameras together.
  std::vector<VideoFrame> frames;
  for (std::size_t i = 0; i < window.size(); ++i)
  {
    frames.push_back({ static_cast<int>(i), check.camera(), window[i].cameraToCT, {} });
  }
  RelocalisationResult result;
  result.trackedErrorPx = windowError(check, window, SimilarityTransform(), nullptr);
  result.bestErrorPx = std::numeric_limits<double>::infinity();
  // Of the poses that lay the contours within the accepted error, the one
  // nearest the tracked pose (1 mm counted as searchMm / searchDeg
  // degrees): in a narrow passage a sideways shift with a turn lays them
  // almost as well, and the tracker's own motion is the better guess
  // between such poses.
  double nearestMove = std::numeric_limits<double>::infinity();
  const double degreesPerMm = options.searchDeg / options.searchMm;
  for (SimilarityTransform move : starts)
  {
    ++result.starts;
    if (!camerasInside(check.model(), frames, move))
    {
      continue;
    }
    for (int iteration = 0; iteration < options.iterations; ++iteration)
    {
      PoseUpdateProblem problem;
      if (!std::isfinite(windowError(check, window, move, &problem.contours)))
      {
        break;
      }
      problem.frames = &frames;
      problem.minScale = 1.0;
      problem.maxScale = 1.0;
      const PoseUpdateResult update = solvePoseUpdate(problem, move);
      int steps = 0;
      const SimilarityTransform next =
        backOffIntoAirway(check.model(), frames, move, update.transform, MaxBackoffSteps, steps);
      if (steps > MaxBackoffSteps)
      {
        break;
      }
      move = next;
    }
    const double errorPx = windowError(check, window, move, nullptr);
    const CameraPose moved = move.apply(current);
    const double mm = cameraPositionError(moved, current);
    const double deg = cameraAngleErrorDeg(moved, current);
    if (!std::isfinite(errorPx) || mm > 2.0 * options.searchMm || deg > 2.0 * options.searchDeg)
    {
      continue;
    }
    result.bestErrorPx = std::min(result.bestErrorPx, errorPx);
    const double size = mm + deg / degreesPerMm;
    if (errorPx <= options.acceptLimitPx() && size < nearestMove)
    {
      nearestMove = size;
      result.correction = move;
    }
  }
  return result;
}

} // namespace vimlop
