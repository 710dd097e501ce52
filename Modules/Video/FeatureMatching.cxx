#include <vimlop/Video/FeatureMatching.h>

#include <algorithm>
#include <limits>

namespace vimlop::detail
{

namespace
{

/// The two nearest candidates so far, by the rule of OpenCV's k-nearest
/// search: a later candidate at an equal distance goes behind an earlier one.
struct TwoNearest
{
  float distance[2] = { std::numeric_limits<float>::max(), std::numeric_limits<float>::max() };
  int index[2] = { -1, -1 };

  void offer(float d, int i)
  {
    if (!(d < this->distance[1]))
    {
      return;
    }
    if (d < this->distance[0])
    {
      this->distance[1] = this->distance[0];
      this->index[1] = this->index[0];
      this->distance[0] = d;
      this->index[0] = i;
    }
    else
    {
      this->distance[1] = d;
      this->index[1] = i;
    }
  }

  /// The nearest, if it passes the ratio test; else -1.
  int distinct(double ratio) const
  {
    const bool passes = this->index[1] >= 0 && this->distance[0] < ratio * this->distance[1];
    return passes ? this->index[0] : -1;
  }
};

} // namespace

std::vector<std::pair<int, int>> mutualNearestMatches(
  const cv::Mat& a, const cv::Mat& b, double ratio)
{
  std::vector<std::pair<int, int>> result;
  if (a.rows < 2 || b.rows < 2)
  {
    return result;
  }
  std::vector<TwoNearest> forward(static_cast<size_t>(a.rows));
  std::vector<TwoNearest> backward(static_cast<size_t>(b.rows));
  // 256 rows of 4000 distances are 4 MB: the whole matrix of two frames of
  // 4000 features would be 64 MB per thread.
  constexpr int blockRows = 256;
  cv::Mat distances;
  for (int begin = 0; begin < a.rows; begin += blockRows)
  {
    const int end = std::min(a.rows, begin + blockRows);
    // The matcher's own distances (OpenCV's brute-force search calls this),
    // so that the matches do not change by a rounding.
    cv::batchDistance(a.rowRange(begin, end), b, distances, CV_32F, cv::noArray(), cv::NORM_L2);
    for (int i = begin; i < end; ++i)
    {
      const float* row = distances.ptr<float>(i - begin);
      for (int j = 0; j < b.rows; ++j)
      {
        forward[static_cast<size_t>(i)].offer(row[j], j);
        backward[static_cast<size_t>(j)].offer(row[j], i);
      }
    }
  }
  for (int i = 0; i < a.rows; ++i)
  {
    const int j = forward[static_cast<size_t>(i)].distinct(ratio);
    if (j >= 0 && backward[static_cast<size_t>(j)].distinct(ratio) == i)
    {
      result.emplace_back(i, j);
    }
  }
  return result;
}

} // namespace vimlop::detail
