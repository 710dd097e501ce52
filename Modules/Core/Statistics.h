#ifndef vimlop_Statistics_h
#define vimlop_Statistics_h

#include <vector>

namespace vimlop
{

/// @brief Summary statistics of a sample (empty sample: all zero).
struct Summary
{
  double mean = 0.0;
  double median = 0.0;
  double p95 = 0.0;
  double max = 0.0;
};

/// @brief Mean, median, 95th percentile (linear interpolation) and maximum.
Summary summarize(std::vector<double> values);

} // namespace vimlop

#endif
