#include <vimlop/Core/OutlierRejection.h>

#include <vimlop/Core/ChiSquare.h>
#include <vimlop/Core/Correspondences.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace vimlop
{

std::vector<char> rejectPointOutliers(const std::vector<Eigen::Vector3d>& residualsCT,
  const std::vector<Eigen::Matrix3d>& covariances, const Eigen::Matrix3d& rotation,
  const std::vector<double>& matchCosts, double trimFraction, double chiSquareThreshold)
{
  const size_t n = residualsCT.size();
  std::vector<char> inlier(n, 1);
  // Trimming: the highest costs go first; ties broken by index for determinism.
  const size_t trimmed = std::min(n, static_cast<size_t>(std::ceil(trimFraction * n - 1e-9)));
  if (trimmed > 0)
  {
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(
      order.begin(), order.end(), [&](int a, int b) { return matchCosts[a] > matchCosts[b]; });
    for (size_t k = 0; k < trimmed; ++k)
    {
      inlier[order[k]] = 0;
    }
  }
  double sum = 0.0;
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i)
  {
    if (inlier[i])
    {
      sum += residualsCT[i].squaredNorm();
      ++kept;
    }
  }
  const double sigma2 = kept > 0 ? sum / kept : 0.0;
  for (size_t i = 0; i < n; ++i)
  {
    if (!inlier[i])
    {
      continue;
    }
    const Eigen::Vector3d d = rotation.transpose() * residualsCT[i];
    const Eigen::Matrix3d inflated = covariances[i] + sigma2 * Eigen::Matrix3d::Identity();
    if (d.dot(inflated.ldlt().solve(d)) > chiSquareThreshold)
    {
      inlier[i] = 0;
    }
  }
  return inlier;
}

std::vector<char> rejectContourOutliers(const std::vector<ContourMatch>& matches,
  const ContourMatchOptions& matchOptions, double squaredDistancePx2, double squaredAngleRad2,
  double chiSquareProbability, double maxOutlierFraction)
{
  const double positionThreshold = chiSquareQuantile(chiSquareProbability, 2);
  const double angleThreshold = chiSquareQuantile(chiSquareProbability, 1);
  const Eigen::Matrix2d inflated =
    matchOptions.positionCovariancePx2 + squaredDistancePx2 * Eigen::Matrix2d::Identity();
  const Eigen::Matrix2d information = inflated.inverse();
  const double angleVariance =
    (matchOptions.kappa > 0.0 ? 1.0 / matchOptions.kappa : 1e300) + squaredAngleRad2;

  std::vector<char> inlier(matches.size(), 0);
  // Each matched point's worst test statistic relative to its threshold.
  std::vector<std::pair<double, int>> failing;
  int matched = 0;
  for (int i = 0; i < static_cast<int>(matches.size()); ++i)
  {
    const ContourMatch& m = matches[i];
    if (m.model < 0)
    {
      continue;
    }
    ++matched;
    const double positionStatistic = m.errorPx.dot(information * m.errorPx);
    const double angleStatistic = m.angleRad * m.angleRad / angleVariance;
    const double ratio =
      std::max(positionStatistic / positionThreshold, angleStatistic / angleThreshold);
    if (ratio > 1.0)
    {
      failing.emplace_back(ratio, i);
    }
    else
    {
      inlier[i] = 1;
    }
  }
  const size_t cap = static_cast<size_t>(std::floor(maxOutlierFraction * matched + 1e-9));
  if (failing.size() > cap)
  {
    // Too many for the per-frame cap: only the worst `cap` are outliers.
    std::stable_sort(failing.begin(), failing.end(),
      [](const auto& a, const auto& b) { return a.first > b.first; });
    for (size_t k = cap; k < failing.size(); ++k)
    {
      inlier[failing[k].second] = 1;
    }
  }
  return inlier;
}

namespace
{

/// The median of `values` scaled to the mean of σ² χ²_k (0 for none).
double scaledMedian(std::vector<double>& values, int degreesOfFreedom)
{
  if (values.empty())
  {
    return 0.0;
  }
  // The upper median: deterministic, and the same whatever the order.
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle * degreesOfFreedom / chiSquareQuantile(0.5, degreesOfFreedom);
}

} // namespace

ContourErrorSpread contourErrorSpread(const std::vector<FrameCorrespondences>& frames, bool robust)
{
  // The means need only sums; the medians keep the values (every iteration
  // of a registration calls this, so the default path allocates nothing).
  double sumDistance2 = 0.0;
  double sumAngle2 = 0.0;
  int matched = 0;
  std::vector<double> distances2;
  std::vector<double> angles2;
  for (const FrameCorrespondences& f : frames)
  {
    for (const ContourMatch& m : f.matches)
    {
      if (m.model < 0)
      {
        continue;
      }
      const double d2 = m.errorPx.squaredNorm();
      const double a2 = m.angleRad * m.angleRad;
      sumDistance2 += d2;
      sumAngle2 += a2;
      ++matched;
      if (robust)
      {
        distances2.push_back(d2);
        angles2.push_back(a2);
      }
    }
  }
  ContourErrorSpread s;
  if (robust)
  {
    s.squaredDistancePx2 = scaledMedian(distances2, 2);
    s.squaredAngleRad2 = scaledMedian(angles2, 1);
  }
  else if (matched > 0)
  {
    s.squaredDistancePx2 = sumDistance2 / matched;
    s.squaredAngleRad2 = sumAngle2 / matched;
  }
  return s;
}

} // namespace vimlop
