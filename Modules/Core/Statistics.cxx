#include "Statistics.h"

#include <algorithm>
#include <cmath>
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
  s.max = values.back();
  return s;
}

} // namespace vimlop
