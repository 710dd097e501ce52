#include <vimlop/Video/SfmReconstructor.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TaskPool.h>
#include <vimlop/Video/FeatureMatching.h>
#include <vimlop/Video/SfmGeometry.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <optional>

namespace vimlop::detail
{

namespace
{

class UnionFind
{
public:
  explicit UnionFind(int n)
    : Parent(static_cast<size_t>(n))
  {
    std::iota(this->Parent.begin(), this->Parent.end(), 0);
  }
  int find(int a)
  {
    while (this->Parent[a] != a)
    {
      this->Parent[a] = this->Parent[this->Parent[a]];
      a = this->Parent[a];
    }
    return a;
  }
  void unite(int a, int b)
  {
    a = this->find(a);
    b = this->find(b);
    if (a != b)
    {
      this->Parent[std::max(a, b)] = std::min(a, b);
    }
  }

private:
  std::vector<int> Parent;
};

} // namespace

void SfmReconstructor::detect()
{
  const int n = static_cast<int>(this->Frames.size());
  std::vector<double> counts(static_cast<size_t>(n), 0.0);
  this->Features.assign(static_cast<size_t>(n), FrameFeatures());
  // One frame per task, each with its own detector: the features of a frame
  // do not depend on the thread that found them.
  TaskPool(this->O.threads)
    .run(n,
      [&](int i)
      {
        const cv::Mat& frame = this->Frames[static_cast<size_t>(i)];
        cv::Mat grey;
        if (frame.channels() == 3 && this->O.channel == StructureFromMotionChannel::Green)
        {
          cv::extractChannel(frame, grey, 1);
        }
        else if (frame.channels() == 3)
        {
          cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
        }
        else
        {
          grey = frame;
        }
        const cv::Ptr<cv::SIFT> sift =
          cv::SIFT::create(this->O.maxFeatures, 3, this->O.contrastThreshold, 10.0, 1.6);
        FrameFeatures& f = this->Features[static_cast<size_t>(i)];
        // Outside the mask (the field stop's border and edge) there is no
        // texture of the anatomy, only the edge's corners, which do not move with it.
        if (this->FeatureMask.empty())
        {
          sift->detectAndCompute(grey, cv::noArray(), f.keypoints, f.descriptors);
        }
        else
        {
          sift->detectAndCompute(grey, this->FeatureMask, f.keypoints, f.descriptors);
        }
        counts[static_cast<size_t>(i)] = static_cast<double>(f.keypoints.size());
        if (static_cast<int>(f.keypoints.size()) < this->O.minFeatures)
        {
          f.keypoints.clear();
          f.descriptors = cv::Mat();
        }
      });
  const Summary s = summarize(counts);
  this->say("SIFT features per frame: median " + std::to_string(static_cast<int>(s.median)));
  int usable = 0;
  for (const FrameFeatures& f : this->Features)
  {
    usable += !f.keypoints.empty();
  }
  if (usable < 2)
  {
    throw Error("SfM cannot initialise: the frames have too little texture (median " +
      std::to_string(static_cast<int>(s.median)) + " SIFT features per frame; at least " +
      std::to_string(this->O.minFeatures) + " needed in two frames)");
  }
}

void SfmReconstructor::match()
{
  /// What one pair of frames gave: verified matches, or why not.
  struct PairOutcome
  {
    std::optional<PairMatches> pair;
    double medianMotionPx = 0.0; ///< 0 when too few candidates to tell
    bool isStatic = false;
  };
  const cv::Mat k = cameraMatrix(this->K);
  const int n = static_cast<int>(this->Frames.size());
  std::vector<std::pair<int, int>> frames;
  for (int i = 0; i < n; ++i)
  {
    for (int j = i + 1; j < n && j <= i + this->O.matchWindow; ++j)
    {
      frames.emplace_back(i, j);
    }
  }
  // Each pair is matched and verified on its own (RANSAC draws from a
  // generator seeded per call) and the outcomes are merged in pair order,
  // so the matches are the same for any number of threads.
  std::vector<PairOutcome> outcomes(frames.size());
  TaskPool(this->O.threads)
    .run(static_cast<int>(frames.size()),
      [&](int t)
      {
        const auto [i, j] = frames[static_cast<size_t>(t)];
        PairOutcome& outcome = outcomes[static_cast<size_t>(t)];
        const std::vector<std::pair<int, int>> candidates = mutualNearestMatches(
          this->Features[i].descriptors, this->Features[j].descriptors, this->O.ratio);
        if (static_cast<int>(candidates.size()) < this->O.minPairMatches)
        {
          return;
        }
        std::vector<cv::Point2d> a;
        std::vector<cv::Point2d> b;
        std::vector<double> motion;
        for (const auto& [p, q] : candidates)
        {
          a.push_back(this->Features[i].keypoints[p].pt);
          b.push_back(this->Features[j].keypoints[q].pt);
          motion.push_back(cv::norm(a.back() - b.back()));
        }
        // Frames that hardly differ carry no epipolar geometry (any essential
        // matrix fits them); remember that they were seen, for the message.
        outcome.medianMotionPx = summarize(motion).median;
        if (outcome.medianMotionPx < this->O.minMotionPx)
        {
          outcome.isStatic = true;
          return;
        }
        cv::Mat mask;
        const cv::Mat e =
          cv::findEssentialMat(a, b, k, cv::RANSAC, 0.999, this->O.essentialThresholdPx, mask);
        if (e.rows != 3 || e.cols != 3)
        {
          return; // degenerate (several solutions or none)
        }
        PairMatches pair;
        pair.first = i;
        pair.second = j;
        pair.essential = e;
        for (size_t m = 0; m < candidates.size(); ++m)
        {
          if (mask.at<unsigned char>(static_cast<int>(m)))
          {
            pair.matches.push_back(candidates[m]);
          }
        }
        if (static_cast<int>(pair.matches.size()) >= this->O.minPairMatches)
        {
          outcome.pair = std::move(pair);
        }
      });
  for (PairOutcome& outcome : outcomes)
  {
    this->LargestMotionPx = std::max(this->LargestMotionPx, outcome.medianMotionPx);
    this->StaticPairs += outcome.isStatic;
    if (outcome.pair)
    {
      this->Pairs.push_back(std::move(*outcome.pair));
    }
  }
  this->say(std::to_string(this->Pairs.size()) + " frame pairs with verified matches");
  if (this->Pairs.empty() && this->StaticPairs > 0)
  {
    char text[300];
    std::snprintf(text, sizeof(text),
      "SfM cannot initialise: the camera hardly moves (features move by at most %.2f px "
      "between the frames compared, at least %.2f px needed)",
      this->LargestMotionPx, this->O.minMotionPx);
    throw Error(text);
  }
  if (this->Pairs.empty())
  {
    throw Error("SfM cannot initialise: no two frames share " +
      std::to_string(this->O.minPairMatches) +
      " verified feature matches (too little texture, or frames that do not overlap)");
  }
}

void SfmReconstructor::buildTracks()
{
  std::vector<int> offset(this->Frames.size() + 1, 0);
  for (size_t f = 0; f < this->Frames.size(); ++f)
  {
    offset[f + 1] = offset[f] + static_cast<int>(this->Features[f].keypoints.size());
  }
  UnionFind sets(offset.back());
  for (const PairMatches& pair : this->Pairs)
  {
    for (const auto& [a, b] : pair.matches)
    {
      sets.unite(offset[pair.first] + a, offset[pair.second] + b);
    }
  }
  std::map<int, std::vector<std::pair<int, int>>> groups;
  for (size_t f = 0; f < this->Frames.size(); ++f)
  {
    for (int k = 0; k < static_cast<int>(this->Features[f].keypoints.size()); ++k)
    {
      groups[sets.find(offset[f] + k)].emplace_back(static_cast<int>(f), k);
    }
  }
  int conflicting = 0;
  for (auto& [root, features] : groups)
  {
    if (features.size() < 2)
    {
      continue;
    }
    // A track with two features in one frame joined a mismatch: drop it.
    bool conflict = false;
    for (size_t a = 1; a < features.size() && !conflict; ++a)
    {
      conflict = features[a].first == features[a - 1].first;
    }
    if (conflict)
    {
      ++conflicting;
      continue;
    }
    Track t;
    t.features = std::move(features);
    this->Tracks.push_back(std::move(t));
  }
  this->TrackOf.assign(this->Frames.size(), std::map<int, int>());
  for (size_t t = 0; t < this->Tracks.size(); ++t)
  {
    for (const auto& [frame, keypoint] : this->Tracks[t].features)
    {
      this->TrackOf[frame][keypoint] = static_cast<int>(t);
    }
  }
  this->say(std::to_string(this->Tracks.size()) + " tracks (" + std::to_string(conflicting) +
    " dropped for conflicts)");
}

} // namespace vimlop::detail
