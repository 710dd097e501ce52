#include <vimlop/Pipeline/TrackerLag.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Pipeline/EndoscopeTracker.h>
#include <vimlop/Pipeline/TrackerRecording.h>
#include <vimlop/Video/TrackerTrajectory.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace vimlop
{

void TrackerLagOptions::validate() const
{
  auto refuse = [](const char* what, double value)
  { throw Error(formatText("tracker lag: %s, not %g", what, value)); };
  if (!(this->maxLagS >= 0.0 && this->maxLagS <= 2.0))
  {
    refuse("the largest lag searched must lie in [0, 2] s", this->maxLagS);
  }
  if (!(this->stepS > 0.0 && std::isfinite(this->stepS)))
  {
    refuse("the search's step must be positive (s)", this->stepS);
  }
  if (this->maxLagS > 0.0 && this->maxLagS < 2.0 * this->stepS)
  {
    // The least must lie inside the grid, between two neighbours.
    refuse("the largest lag searched must be 0 or at least two steps", this->maxLagS);
  }
  if (this->maxLagS > 0.0 && this->maxLagS / this->stepS > 10000.0)
  {
    refuse("the search must have at most 10000 steps either way", this->maxLagS / this->stepS);
  }
  if (!(this->spanS > 0.0 && this->spanS <= 10.0))
  {
    refuse("the displacements' span must lie in (0, 10] s", this->spanS);
  }
  if (this->minPairs < 10)
  {
    refuse("an estimate needs at least 10 pairs of frames", this->minPairs);
  }
  if (this->everyFrames < 1)
  {
    refuse("the estimate is made again after at least 1 frame", this->everyFrames);
  }
  if (this->windowFrames < this->minPairs)
  {
    refuse("the window must hold at least the pairs an estimate needs", this->windowFrames);
  }
}

TrackerLag::TrackerLag(const TrackerTrajectory& recording, const Eigen::Matrix4d& trackerToCT,
  const TrackerLagOptions& options)
  : Recording(recording)
  , ToCT(trackerToCT)
  , Options(options)
{
  options.validate();
}

std::optional<TrackerPrior> TrackerLag::priorAt(double frameTimeS) const
{
  return trackerPriorAt(this->Recording, this->ToCT, frameTimeS + this->Lag);
}

void TrackerLag::learn(double frameTimeS, const TrackedFrame& frame)
{
  if (this->Options.maxLagS == 0.0 || frame.state == TrackingState::Lost)
  {
    return;
  }
  this->Times.push_back(frameTimeS);
  this->Centres.push_back(frame.cameraToCT.centre);
  if (static_cast<int>(this->Times.size()) > this->Options.windowFrames)
  {
    this->Times.pop_front();
    this->Centres.pop_front();
  }
  ++this->SinceEstimate;
  if (static_cast<int>(this->Times.size()) < this->Options.minPairs ||
    this->SinceEstimate < this->Options.everyFrames)
  {
    return;
  }
  this->SinceEstimate = 0;
  if (const auto found =
        fit(this->Recording, this->ToCT, this->Times, this->Centres, this->Options))
  {
    this->Last = found;
    this->Lag = found->lagS;
  }
}

std::optional<TrackerLagEstimate> TrackerLag::fit(const TrackerTrajectory& recording,
  const Eigen::Matrix4d& trackerToCT, const std::deque<double>& timesS,
  const std::deque<Eigen::Vector3d>& centresCT, const TrackerLagOptions& options)
{
  const int steps = static_cast<int>(std::floor(options.maxLagS / options.stepS + 1e-9));
  if (steps < 2 || recording.samples().empty())
  {
    return std::nullopt;
  }
  const double reachS = steps * options.stepS;
  auto covered = [&](double t)
  { return t - reachS >= recording.startS() && t + reachS <= recording.endS(); };
  // Each frame with the first one at least spanS later, when that one is
  // no more than twice spanS later (not across a lost stretch), both
  // covered by the recording at every lag tried, so that each lag is
  // judged on the same pairs.
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  std::size_t later = 0;
  for (std::size_t i = 0; i < timesS.size(); ++i)
  {
    later = std::max(later, i + 1);
    while (later < timesS.size() && timesS[later] - timesS[i] < options.spanS)
    {
      ++later;
    }
    if (later < timesS.size() && timesS[later] - timesS[i] <= 2.0 * options.spanS &&
      covered(timesS[i]) && covered(timesS[later]))
    {
      pairs.emplace_back(i, later);
    }
  }
  if (static_cast<int>(pairs.size()) < options.minPairs)
  {
    return std::nullopt;
  }
  // Displacements need only the registration's linear part.
  const Eigen::Matrix3d linear = trackerToCT.topLeftCorner<3, 3>();
  // The best 80 % of the pairs: a jump of the video (a recast from the
  // tracker, a relocalisation) is no motion, and no lag explains it.
  const std::size_t kept = std::max<std::size_t>(1, (pairs.size() * 4) / 5);
  std::vector<double> squared(pairs.size());
  auto disagreement2 = [&](double lagS)
  {
    for (std::size_t k = 0; k < pairs.size(); ++k)
    {
      const auto [i, j] = pairs[k];
      const Eigen::Vector3d tracker = linear *
        (*recording.positionAt(timesS[j] + lagS) - *recording.positionAt(timesS[i] + lagS));
      squared[k] = (tracker - (centresCT[j] - centresCT[i])).squaredNorm();
    }
    std::nth_element(
      squared.begin(), squared.begin() + static_cast<std::ptrdiff_t>(kept - 1), squared.end());
    double sum = 0.0;
    for (std::size_t k = 0; k < kept; ++k)
    {
      sum += squared[k];
    }
    return sum / static_cast<double>(kept);
  };
  std::vector<double> cost;
  cost.reserve(static_cast<std::size_t>(2 * steps + 1));
  for (int k = -steps; k <= steps; ++k)
  {
    cost.push_back(disagreement2(k * options.stepS));
  }
  const auto least = std::min_element(cost.begin(), cost.end());
  const std::size_t best = static_cast<std::size_t>(least - cost.begin());
  if (best == 0 || best + 1 == cost.size() || cost.front() < 2.0 * *least ||
    cost.back() < 2.0 * *least)
  {
    return std::nullopt;
  }
  // The parabola's vertex through the least and its neighbours.
  const double below = cost[best - 1], above = cost[best + 1];
  const double curvature = below - 2.0 * *least + above;
  const double offsetSteps = curvature > 0.0 ? 0.5 * (below - above) / curvature : 0.0;
  TrackerLagEstimate e;
  e.lagS = (static_cast<double>(best) - steps + offsetSteps) * options.stepS;
  e.disagreementMm = std::sqrt(disagreement2(e.lagS));
  e.disagreementAtZeroMm = std::sqrt(cost[static_cast<std::size_t>(steps)]);
  e.pairs = static_cast<int>(pairs.size());
  return e;
}

} // namespace vimlop
