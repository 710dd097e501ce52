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
  double p99 = 0.0;
  double max = 0.0;
};

/// @brief Mean, median, 95th and 99th percentiles (linear interpolation) and maximum.
Summary summarize(std::vector<double> values);

/**
 * @brief Area under the ROC curve of a score that should be higher for
 * `positives` than for `negatives`: the probability that a random positive
 * scores above a random negative, ties counting one half. NaN when either
 * group is empty.
 */
double rocAuc(const std::vector<double>& positives, const std::vector<double>& negatives);

/**
 * @brief The threshold t that best separates the groups by "score > t means
 * positive", maximising Youden's J = true-positive rate - false-positive rate;
 * t is halfway between two neighbouring scores. NaN when either group is empty.
 */
double bestSeparatingThreshold(
  const std::vector<double>& positives, const std::vector<double>& negatives);

} // namespace vimlop

#endif
