#ifndef vimlop_FeatureMatching_h
#define vimlop_FeatureMatching_h

// Private to the Video module (not installed): the feature matching of
// SfmReconstructor.

#include <opencv2/core.hpp>

#include <utility>
#include <vector>

namespace vimlop::detail
{

/**
 * @brief Mutual nearest neighbours (Euclidean) between the rows of two float
 * descriptor matrices that pass Lowe's ratio test both ways: (row of a, row of b)
 * pairs in order of the row of a.
 *
 * They are the matches of OpenCV's brute-force 2-nearest search run each way,
 * ties included (of two candidates at one distance the earlier row is the
 * nearer), but each distance is computed once for both directions, in
 * blocks of rows: the searches computed each twice, and that was most of
 * the SfM time.
 */
std::vector<std::pair<int, int>> mutualNearestMatches(
  const cv::Mat& a, const cv::Mat& b, double ratio);

} // namespace vimlop::detail

#endif
