#include <vimlop/Video/FeatureMatching.h>

#include <gtest/gtest.h>

#include <opencv2/features2d.hpp>

using namespace vimlop;
using detail::mutualNearestMatches;

namespace
{

/// The matches of OpenCV's brute-force 2-nearest search run both ways.
std::vector<std::pair<int, int>> matcherBothWays(const cv::Mat& a, const cv::Mat& b, double ratio)
{
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> forward;
  std::vector<std::vector<cv::DMatch>> backward;
  matcher.knnMatch(a, b, forward, 2);
  matcher.knnMatch(b, a, backward, 2);
  const auto distinct = [ratio](const std::vector<cv::DMatch>& m)
  { return m.size() == 2 && m[0].distance < ratio * m[1].distance ? m[0].trainIdx : -1; };
  std::vector<std::pair<int, int>> result;
  for (const std::vector<cv::DMatch>& m : forward)
  {
    const int j = distinct(m);
    if (j >= 0 && distinct(backward[static_cast<size_t>(j)]) == m[0].queryIdx)
    {
      result.emplace_back(m[0].queryIdx, j);
    }
  }
  return result;
}

/// SIFT-like descriptors: `rows` random ones, then copies of `of`'s rows
/// with a noise that grows from 0 to `noise` (from sure matches to none).
cv::Mat descriptors(int rows, const cv::Mat& of, double noise, uint64_t seed)
{
  cv::RNG rng(seed);
  cv::Mat d(rows + of.rows, 128, CV_32F);
  rng.fill(d, cv::RNG::UNIFORM, 0.0, 60.0);
  for (int r = 0; r < of.rows; ++r)
  {
    cv::Mat n(1, 128, CV_32F);
    rng.fill(n, cv::RNG::NORMAL, 0.0, noise * r / of.rows);
    d.row(rows + r) = of.row(r) + n;
  }
  return d;
}

} // namespace

TEST(FeatureMatching, GivesTheMatchesOfTheBruteForceMatcherRunBothWays)
{
  // Over 256 rows, so that the distances come in several blocks; half the
  // rows of b are noisy copies of rows of a (true matches, some ambiguous),
  // and two of b's rows are one copy of a's first row (a tie).
  const cv::Mat a = descriptors(700, cv::Mat(), 0.0, 1);
  const cv::Mat copies = a.rowRange(100, 500).clone();
  cv::Mat b = descriptors(380, copies, 30.0, 2);
  const cv::Mat tie = a.row(0) + 1.0f;
  tie.copyTo(b.row(1));
  tie.copyTo(b.row(2));
  for (const double ratio : { 0.6, 0.8, 1.2 })
  {
    const std::vector<std::pair<int, int>> matches = mutualNearestMatches(a, b, ratio);
    EXPECT_EQ(matches, matcherBothWays(a, b, ratio)) << "ratio " << ratio;
    EXPECT_GT(matches.size(), 100u) << "ratio " << ratio;
  }
  // Only a ratio over 1 lets a tie through: the earlier row is the nearer.
  EXPECT_EQ(mutualNearestMatches(a, b, 1.2).front(), std::make_pair(0, 1));
}

TEST(FeatureMatching, FindsNoMatchWithFewerThanTwoDescriptorsOnASide)
{
  const cv::Mat a = descriptors(10, cv::Mat(), 0.0, 3);
  EXPECT_TRUE(mutualNearestMatches(a, a.rowRange(0, 1), 0.8).empty());
  EXPECT_TRUE(mutualNearestMatches(cv::Mat(), a, 0.8).empty());
  EXPECT_EQ(mutualNearestMatches(a, a, 0.8).size(), 10u);
}
