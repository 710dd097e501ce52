#include <vimlop/Video/StructureFromMotion.h>

#include <vimlop/Video/BundleAdjustment.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/Statistics.h>

#include <Eigen/Dense>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <ostream>

namespace vimlop
{

namespace
{

constexpr double Degree = M_PI / 180.0;

struct FrameFeatures
{
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
};

struct PairMatches
{
  int first = 0;
  int second = 0;
  std::vector<std::pair<int, int>> matches; ///< keypoint indices, verified
  cv::Mat essential;
};

/// One feature track: a keypoint per frame, and the point it became.
struct Track
{
  std::vector<std::pair<int, int>> features; ///< (frame, keypoint)
  int point = -1;
};

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

cv::Mat cameraMatrix(const PinholeCamera& k)
{
  return (cv::Mat_<double>(3, 3) << k.fx, 0.0, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0);
}

Eigen::Vector2d pixelOf(const cv::KeyPoint& k)
{
  return { k.pt.x, k.pt.y };
}

/// Mutual nearest neighbours that pass the ratio test both ways.
std::vector<std::pair<int, int>> matchDescriptors(const cv::Mat& a, const cv::Mat& b, double ratio)
{
  std::vector<std::pair<int, int>> result;
  if (a.rows < 2 || b.rows < 2)
  {
    return result;
  }
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> forward;
  std::vector<std::vector<cv::DMatch>> backward;
  matcher.knnMatch(a, b, forward, 2);
  matcher.knnMatch(b, a, backward, 2);
  std::vector<int> bestBackward(static_cast<size_t>(b.rows), -1);
  for (const std::vector<cv::DMatch>& m : backward)
  {
    if (m.size() == 2 && m[0].distance < ratio * m[1].distance)
    {
      bestBackward[static_cast<size_t>(m[0].queryIdx)] = m[0].trainIdx;
    }
  }
  for (const std::vector<cv::DMatch>& m : forward)
  {
    if (m.size() == 2 && m[0].distance < ratio * m[1].distance &&
      bestBackward[static_cast<size_t>(m[0].trainIdx)] == m[0].queryIdx)
    {
      result.emplace_back(m[0].queryIdx, m[0].trainIdx);
    }
  }
  return result;
}

/// World-to-camera [R | t] of a camera-to-world pose.
Eigen::Matrix<double, 3, 4> projectionOf(const CameraPose& pose)
{
  Eigen::Matrix<double, 3, 4> p;
  p.leftCols<3>() = pose.rotation.transpose();
  p.col(3) = -pose.rotation.transpose() * pose.centre;
  return p;
}

/// Linear multi-view triangulation (DLT) from normalised image points.
Eigen::Vector3d triangulate(const std::vector<Eigen::Matrix<double, 3, 4>>& projections,
  const std::vector<Eigen::Vector2d>& normalised)
{
  Eigen::MatrixXd a(2 * projections.size(), 4);
  for (size_t k = 0; k < projections.size(); ++k)
  {
    a.row(2 * k) = normalised[k].x() * projections[k].row(2) - projections[k].row(0);
    a.row(2 * k + 1) = normalised[k].y() * projections[k].row(2) - projections[k].row(1);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  const Eigen::Vector4d x = svd.matrixV().col(3);
  return x.head<3>() / x[3];
}

class Reconstructor
{
public:
  Reconstructor(const StructureFromMotion::Options& options, const std::vector<cv::Mat>& frames,
    const PinholeCamera& k, std::ostream* log)
    : O(options)
    , Frames(frames)
    , K(k)
    , Log(log)
  {
  }

  SfmReconstruction run(const std::vector<std::string>& names)
  {
    this->detect();
    this->match();
    this->buildTracks();
    this->initialise();
    this->registerRemaining();
    return this->result(names);
  }

private:
  void say(const std::string& text)
  {
    if (this->Log)
    {
      *this->Log << "sfm: " << text << "\n";
    }
  }

  void detect()
  {
    const cv::Ptr<cv::SIFT> sift =
      cv::SIFT::create(this->O.maxFeatures, 3, this->O.contrastThreshold, 10.0, 1.6);
    std::vector<double> counts;
    for (const cv::Mat& frame : this->Frames)
    {
      cv::Mat grey;
      if (frame.channels() == 3 && this->O.channel == StructureFromMotion::Channel::Green)
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
      FrameFeatures f;
      sift->detectAndCompute(grey, cv::noArray(), f.keypoints, f.descriptors);
      counts.push_back(static_cast<double>(f.keypoints.size()));
      if (static_cast<int>(f.keypoints.size()) < this->O.minFeatures)
      {
        f.keypoints.clear();
        f.descriptors = cv::Mat();
      }
      this->Features.push_back(std::move(f));
    }
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

  void match()
  {
    const cv::Mat k = cameraMatrix(this->K);
    const int n = static_cast<int>(this->Frames.size());
    for (int i = 0; i < n; ++i)
    {
      for (int j = i + 1; j < n && j <= i + this->O.matchWindow; ++j)
      {
        const std::vector<std::pair<int, int>> candidates = matchDescriptors(
          this->Features[i].descriptors, this->Features[j].descriptors, this->O.ratio);
        if (static_cast<int>(candidates.size()) < this->O.minPairMatches)
        {
          continue;
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
        const double medianMotion = summarize(motion).median;
        this->LargestMotionPx = std::max(this->LargestMotionPx, medianMotion);
        if (medianMotion < this->O.minMotionPx)
        {
          ++this->StaticPairs;
          continue;
        }
        cv::Mat mask;
        const cv::Mat e =
          cv::findEssentialMat(a, b, k, cv::RANSAC, 0.999, this->O.essentialThresholdPx, mask);
        if (e.rows != 3 || e.cols != 3)
        {
          continue; // degenerate (several solutions or none)
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
          this->Pairs.push_back(std::move(pair));
        }
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

  void buildTracks()
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

  Eigen::Vector2d normalised(const Eigen::Vector2d& pixel) const
  {
    return { (pixel.x() - this->K.cx) / this->K.fx, (pixel.y() - this->K.cy) / this->K.fy };
  }

  void initialise()
  {
    const cv::Mat k = cameraMatrix(this->K);
    double bestScore = -1.0;
    double largestAngle = 0.0;
    double largestDisparity = 0.0;
    const PairMatches* best = nullptr;
    CameraPose bestPose;
    for (const PairMatches& pair : this->Pairs)
    {
      std::vector<cv::Point2d> a;
      std::vector<cv::Point2d> b;
      std::vector<double> disparities;
      for (const auto& [p, q] : pair.matches)
      {
        a.push_back(this->Features[pair.first].keypoints[p].pt);
        b.push_back(this->Features[pair.second].keypoints[q].pt);
        disparities.push_back(cv::norm(a.back() - b.back()));
      }
      largestDisparity = std::max(largestDisparity, summarize(disparities).median);
      cv::Mat r;
      cv::Mat t;
      cv::Mat mask;
      const int inFront = cv::recoverPose(pair.essential, a, b, k, r, t, mask);
      if (inFront < this->O.minPairMatches)
      {
        continue;
      }
      // Second camera: x2 = R x1 + t, so its camera-to-world pose is (R^T, -R^T t).
      Eigen::Matrix3d rotation;
      Eigen::Vector3d translation;
      for (int row = 0; row < 3; ++row)
      {
        translation[row] = t.at<double>(row);
        for (int col = 0; col < 3; ++col)
        {
          rotation(row, col) = r.at<double>(row, col);
        }
      }
      CameraPose second;
      second.rotation = rotation.transpose();
      second.centre = -rotation.transpose() * translation;
      const std::vector<Eigen::Matrix<double, 3, 4>> projections = { projectionOf(CameraPose()),
        projectionOf(second) };
      std::vector<double> angles;
      for (size_t m = 0; m < pair.matches.size(); ++m)
      {
        if (!mask.at<unsigned char>(static_cast<int>(m)))
        {
          continue;
        }
        const Eigen::Vector3d x = triangulate(projections,
          { this->normalised({ a[m].x, a[m].y }), this->normalised({ b[m].x, b[m].y }) });
        const Eigen::Vector3d ray1 = x;
        const Eigen::Vector3d ray2 = x - second.centre;
        angles.push_back(
          std::acos(std::clamp(ray1.normalized().dot(ray2.normalized()), -1.0, 1.0)));
      }
      const double median = summarize(angles).median / Degree;
      largestAngle = std::max(largestAngle, median);
      if (median < this->O.minInitialAngleDeg)
      {
        continue;
      }
      const double score = static_cast<double>(angles.size());
      if (score > bestScore)
      {
        bestScore = score;
        best = &pair;
        bestPose = second;
      }
    }
    if (!best)
    {
      char text[300];
      std::snprintf(text, sizeof(text),
        "SfM cannot initialise: the camera hardly moves (the largest median triangulation angle "
        "of any two frames is %.2f deg, at least %.2f deg needed; median feature motion at most "
        "%.2f px)",
        largestAngle, this->O.minInitialAngleDeg, largestDisparity);
      throw Error(text);
    }
    this->Registered.assign(this->Frames.size(), false);
    this->Poses.assign(this->Frames.size(), CameraPose());
    this->Origin = best->first;
    this->Registered[best->first] = true;
    this->Registered[best->second] = true;
    this->Poses[best->second] = bestPose;
    this->ScaleCamera = best->second;
    this->say("initial pair: frames " + std::to_string(best->first) + " and " +
      std::to_string(best->second) + " (" + std::to_string(static_cast<int>(bestScore)) +
      " matches)");
    this->triangulateTracks();
    this->adjust(20);
  }

  /// Points for tracks seen by at least two registered frames.
  void triangulateTracks()
  {
    for (Track& track : this->Tracks)
    {
      if (track.point >= 0)
      {
        continue;
      }
      std::vector<std::pair<int, Eigen::Vector2d>> seen;
      for (const auto& [frame, keypoint] : track.features)
      {
        if (this->Registered[frame])
        {
          seen.emplace_back(frame, pixelOf(this->Features[frame].keypoints[keypoint]));
        }
      }
      if (seen.size() < 2)
      {
        continue;
      }
      Eigen::Vector3d x;
      std::vector<std::pair<int, Eigen::Vector2d>> kept;
      // Triangulate, drop observations that disagree, once more with the rest.
      for (int round = 0; round < 2 && seen.size() >= 2; ++round)
      {
        std::vector<Eigen::Matrix<double, 3, 4>> projections;
        std::vector<Eigen::Vector2d> normalised;
        for (const auto& [frame, pixel] : seen)
        {
          projections.push_back(projectionOf(this->Poses[frame]));
          normalised.push_back(this->normalised(pixel));
        }
        x = triangulate(projections, normalised);
        kept.clear();
        for (const auto& [frame, pixel] : seen)
        {
          const Eigen::Vector3d c = this->Poses[frame].worldToCamera(x);
          if (c.z() > 0.0 && (this->K.project(c) - pixel).norm() <= this->O.maxReprojectionErrorPx)
          {
            kept.emplace_back(frame, pixel);
          }
        }
        if (kept.size() == seen.size())
        {
          break;
        }
        seen = kept;
      }
      if (kept.size() < 2 || !x.allFinite())
      {
        continue;
      }
      double widest = 0.0;
      for (size_t a = 0; a < kept.size(); ++a)
      {
        for (size_t b = a + 1; b < kept.size(); ++b)
        {
          const Eigen::Vector3d ra = (x - this->Poses[kept[a].first].centre).normalized();
          const Eigen::Vector3d rb = (x - this->Poses[kept[b].first].centre).normalized();
          widest = std::max(widest, std::acos(std::clamp(ra.dot(rb), -1.0, 1.0)));
        }
      }
      if (widest < this->O.minTriangulationAngleDeg * Degree)
      {
        continue;
      }
      track.point = static_cast<int>(this->Points.size());
      this->Points.push_back(x);
      this->Observations.push_back(kept);
    }
  }

  /// Observations of existing points in a newly registered frame, if they agree.
  void addObservations(int frame)
  {
    for (const auto& [keypoint, trackIndex] : this->TrackOf[frame])
    {
      const Track& track = this->Tracks[trackIndex];
      if (track.point < 0)
      {
        continue;
      }
      const Eigen::Vector2d pixel = pixelOf(this->Features[frame].keypoints[keypoint]);
      const Eigen::Vector3d c = this->Poses[frame].worldToCamera(this->Points[track.point]);
      if (c.z() > 0.0 && (this->K.project(c) - pixel).norm() <= this->O.maxReprojectionErrorPx)
      {
        this->Observations[track.point].emplace_back(frame, pixel);
      }
    }
  }

  void adjust(int iterations)
  {
    std::vector<int> cameraOf(this->Frames.size(), -1);
    std::vector<CameraPose> cameras;
    std::vector<PinholeCamera> intrinsics;
    for (size_t f = 0; f < this->Frames.size(); ++f)
    {
      if (this->Registered[f])
      {
        cameraOf[f] = static_cast<int>(cameras.size());
        cameras.push_back(this->Poses[f]);
        intrinsics.push_back(this->K);
      }
    }
    std::vector<BundleAdjustment::Observation> observations;
    for (size_t p = 0; p < this->Points.size(); ++p)
    {
      for (const auto& [frame, pixel] : this->Observations[p])
      {
        observations.push_back({ cameraOf[frame], static_cast<int>(p), pixel });
      }
    }
    BundleAdjustment::Options options;
    options.maxIterations = iterations;
    options.scaleCamera = cameraOf[this->ScaleCamera];
    BundleAdjustment::adjust(
      cameras, this->Points, intrinsics, observations, { cameraOf[this->Origin] }, options);
    for (size_t f = 0; f < this->Frames.size(); ++f)
    {
      if (cameraOf[f] >= 0)
      {
        this->Poses[f] = cameras[cameraOf[f]];
      }
    }
    // Remove observations that the adjusted geometry does not explain.
    for (size_t p = 0; p < this->Points.size(); ++p)
    {
      auto& seen = this->Observations[p];
      seen.erase(std::remove_if(seen.begin(), seen.end(),
                   [&](const std::pair<int, Eigen::Vector2d>& o)
                   {
                     const Eigen::Vector3d c = this->Poses[o.first].worldToCamera(this->Points[p]);
                     return c.z() <= 0.0 ||
                       (this->K.project(c) - o.second).norm() > this->O.maxReprojectionErrorPx;
                   }),
        seen.end());
    }
  }

  void registerRemaining()
  {
    const cv::Mat k = cameraMatrix(this->K);
    std::vector<bool> failed(this->Frames.size(), false);
    while (true)
    {
      // The unregistered frame that sees the most reconstructed points.
      int next = -1;
      int most = 0;
      for (size_t f = 0; f < this->Frames.size(); ++f)
      {
        if (this->Registered[f] || failed[f])
        {
          continue;
        }
        int count = 0;
        for (const auto& [keypoint, trackIndex] : this->TrackOf[f])
        {
          count += this->Tracks[trackIndex].point >= 0 &&
            this->Observations[this->Tracks[trackIndex].point].size() >= 2;
        }
        if (count > most)
        {
          most = count;
          next = static_cast<int>(f);
        }
      }
      if (next < 0 || most < this->O.minRegistrationPoints)
      {
        break;
      }
      std::vector<cv::Point3d> object;
      std::vector<cv::Point2d> image;
      for (const auto& [keypoint, trackIndex] : this->TrackOf[next])
      {
        const int p = this->Tracks[trackIndex].point;
        if (p >= 0 && this->Observations[p].size() >= 2)
        {
          object.emplace_back(this->Points[p].x(), this->Points[p].y(), this->Points[p].z());
          image.push_back(this->Features[next].keypoints[keypoint].pt);
        }
      }
      cv::Mat rvec;
      cv::Mat tvec;
      std::vector<int> inliers;
      const bool found = cv::solvePnPRansac(object, image, k, cv::noArray(), rvec, tvec, false, 500,
        static_cast<float>(this->O.pnpThresholdPx), 0.999, inliers, cv::SOLVEPNP_EPNP);
      if (!found || static_cast<int>(inliers.size()) < this->O.minRegistrationPoints)
      {
        failed[next] = true;
        this->say("frame " + std::to_string(next) + ": only " + std::to_string(inliers.size()) +
          " PnP inliers; not registered");
        continue;
      }
      std::vector<cv::Point3d> objectInliers;
      std::vector<cv::Point2d> imageInliers;
      for (int i : inliers)
      {
        objectInliers.push_back(object[i]);
        imageInliers.push_back(image[i]);
      }
      cv::solvePnPRefineLM(objectInliers, imageInliers, k, cv::noArray(), rvec, tvec);
      cv::Mat r;
      cv::Rodrigues(rvec, r);
      Eigen::Matrix3d rotation;
      Eigen::Vector3d translation;
      for (int row = 0; row < 3; ++row)
      {
        translation[row] = tvec.at<double>(row);
        for (int col = 0; col < 3; ++col)
        {
          rotation(row, col) = r.at<double>(row, col);
        }
      }
      this->Poses[next].rotation = rotation.transpose();
      this->Poses[next].centre = -rotation.transpose() * translation;
      this->Registered[next] = true;
      this->addObservations(next);
      this->triangulateTracks();
      this->adjust(10);
      this->say("frame " + std::to_string(next) + " registered (" + std::to_string(inliers.size()) +
        " PnP inliers), " + std::to_string(this->Points.size()) + " points");
    }
    this->adjust(100);
  }

  SfmReconstruction result(const std::vector<std::string>& names)
  {
    SfmReconstruction r;
    r.source = "builtin";
    // One SfM unit: the mean distance between consecutive registered cameras.
    double path = 0.0;
    int steps = 0;
    int previous = -1;
    for (size_t f = 0; f < this->Frames.size(); ++f)
    {
      if (this->Registered[f])
      {
        if (previous >= 0)
        {
          path += (this->Poses[f].centre - this->Poses[previous].centre).norm();
          ++steps;
        }
        previous = static_cast<int>(f);
      }
    }
    const double scale = steps > 0 && path > 0.0 ? steps / path : 1.0;
    for (size_t f = 0; f < this->Frames.size(); ++f)
    {
      SfmReconstruction::Frame frame;
      frame.name = f < names.size() ? names[f] : "frame" + std::to_string(f);
      frame.registered = this->Registered[f];
      frame.intrinsics = this->K;
      if (frame.registered)
      {
        frame.cameraToSfm = this->Poses[f];
        frame.cameraToSfm.centre *= scale;
      }
      r.frames.push_back(frame);
    }
    for (size_t p = 0; p < this->Points.size(); ++p)
    {
      const auto& seen = this->Observations[p];
      if (static_cast<int>(seen.size()) < this->O.minTrackLength)
      {
        continue;
      }
      SfmReconstruction::Point point;
      point.position = scale * this->Points[p];
      for (const auto& [frame, pixel] : seen)
      {
        point.observations.push_back({ frame, pixel });
      }
      const cv::Mat& image = this->Frames[seen.front().first];
      const int u =
        std::clamp(static_cast<int>(std::lround(seen.front().second.x())), 0, image.cols - 1);
      const int v =
        std::clamp(static_cast<int>(std::lround(seen.front().second.y())), 0, image.rows - 1);
      if (image.channels() == 3)
      {
        const cv::Vec3b bgr = image.at<cv::Vec3b>(v, u);
        point.colour = Eigen::Vector3i(bgr[2], bgr[1], bgr[0]);
      }
      else
      {
        const int g = image.at<unsigned char>(v, u);
        point.colour = Eigen::Vector3i(g, g, g);
      }
      r.points.push_back(std::move(point));
    }
    const double rms = std::max(0.1, r.rmsReprojectionErrorPx());
    r.computeCovariances(rms);
    int unregistered = 0;
    for (const SfmReconstruction::Frame& f : r.frames)
    {
      unregistered += !f.registered;
    }
    this->say(std::to_string(r.numberOfRegisteredFrames()) + " of " +
      std::to_string(r.frames.size()) + " frames registered" +
      (unregistered ? " (the others are dropped)" : "") + ", " + std::to_string(r.points.size()) +
      " points, RMS reprojection error " + std::to_string(r.rmsReprojectionErrorPx()) + " px");
    return r;
  }

  const StructureFromMotion::Options& O;
  const std::vector<cv::Mat>& Frames;
  PinholeCamera K;
  std::ostream* Log;
  std::vector<FrameFeatures> Features;
  std::vector<PairMatches> Pairs;
  std::vector<Track> Tracks;
  std::vector<std::map<int, int>> TrackOf; ///< per frame: keypoint -> track
  std::vector<bool> Registered;
  std::vector<CameraPose> Poses;
  int StaticPairs = 0;
  double LargestMotionPx = 0.0;
  int Origin = 0;
  int ScaleCamera = 0;
  std::vector<Eigen::Vector3d> Points;
  std::vector<std::vector<std::pair<int, Eigen::Vector2d>>> Observations;
};

} // namespace

StructureFromMotion::StructureFromMotion()
  : StructureFromMotion(Options())
{
}

StructureFromMotion::StructureFromMotion(const Options& options)
  : Opts(options)
{
}

SfmReconstruction StructureFromMotion::reconstruct(const std::vector<cv::Mat>& frames,
  const PinholeCamera& intrinsics, const std::vector<std::string>& names, std::ostream* log) const
{
  if (frames.size() < 2)
  {
    throw Error("SfM needs at least 2 frames, got " + std::to_string(frames.size()));
  }
  intrinsics.validate();
  auto nameOf = [&](size_t i) { return i < names.size() ? names[i] : "frame" + std::to_string(i); };
  for (size_t i = 0; i < frames.size(); ++i)
  {
    if (frames[i].empty() || frames[i].depth() != CV_8U ||
      (frames[i].channels() != 1 && frames[i].channels() != 3))
    {
      throw Error("SfM: frame '" + nameOf(i) + "' is not an 8-bit grey or colour image");
    }
    if (frames[i].size() != frames[0].size())
    {
      throw Error("SfM: frame '" + nameOf(i) + "' is " + std::to_string(frames[i].cols) + "x" +
        std::to_string(frames[i].rows) + " but '" + nameOf(0) + "' is " +
        std::to_string(frames[0].cols) + "x" + std::to_string(frames[0].rows));
    }
  }
  if (intrinsics.widthPx != frames[0].cols || intrinsics.heightPx != frames[0].rows)
  {
    throw Error("SfM: the intrinsics are for " + std::to_string(intrinsics.widthPx) + "x" +
      std::to_string(intrinsics.heightPx) + " pixels but the frames are " +
      std::to_string(frames[0].cols) + "x" + std::to_string(frames[0].rows));
  }
  Reconstructor reconstructor(this->Opts, frames, intrinsics, log);
  return reconstructor.run(names);
}

} // namespace vimlop
