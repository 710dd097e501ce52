#include <vimlop/Core/Statistics.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace vimlop
{

namespace
{

double quantile(const std::vector<double>& sorted, double q)
{
  const double position = q * (sorted.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(position));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (position - lo) * (sorted[hi] - sorted[lo]);
}

} // namespace

Summary summarize(std::vector<double> values)
{
  Summary s;
  if (values.empty())
  {
    return s;
  }
  std::sort(values.begin(), values.end());
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / values.size();
  s.median = quantile(values, 0.5);
  s.p95 = quantile(values, 0.95);
  s.p99 = quantile(values, 0.99);
  s.max = values.back();
  return s;
}

double rocAuc(const std::vector<double>& positives, const std::vector<double>& negatives)
{
  if (positives.empty() || negatives.empty())
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  double wins = 0.0;
  for (double p : positives)
  {
    for (double n : negatives)
    {
      wins += p > n ? 1.0 : (p == n ? 0.5 : 0.0);
    }
  }
  return wins / (static_cast<double>(positives.size()) * static_cast<double>(negatives.size()));
}

double bestSeparatingThreshold(
  const std::vector<double>& positives, const std::vector<double>& negatives)
{
  if (positives.empty() || negatives.empty())
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  std::vector<double> scores = positives;
  scores.insert(scores.end(), negatives.begin(), negatives.end());
  std::sort(scores.begin(), scores.end());
  scores.erase(std::unique(scores.begin(), scores.end()), scores.end());
  // Candidates: below everything, between neighbours, above everything.
  std::vector<double> candidates{ scores.front() - 1.0 };
  for (size_t i = 0; i + 1 < scores.size(); ++i)
  {
    candidates.push_back(0.5 * (scores[i] + scores[i + 1]));
  }
  candidates.push_back(scores.back() + 1.0);
  double best = candidates.front();
  double bestJ = -2.0;
  for (double t : candidates)
  {
    const double tpr = static_cast<double>(std::count_if(
                         positives.begin(), positives.end(), [t](double p) { return p > t; })) /
      static_cast<double>(positives.size());
    const double fpr = static_cast<double>(std::count_if(
                         negatives.begin(), negatives.end(), [t](double n) { return n > t; })) /
      static_cast<double>(negatives.size());
    if (tpr - fpr > bestJ)
    {
      bestJ = tpr - fpr;
      best = t;
    }
  }
  return best;
}

} // namespace vimlop
