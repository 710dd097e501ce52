#include <vimlop/Video/SfmReconstructor.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Video/SfmGeometry.h>

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vimlop::detail
{

void SfmReconstructor::initialise()
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
      angles.push_back(std::acos(std::clamp(ray1.normalized().dot(ray2.normalized()), -1.0, 1.0)));
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

} // namespace vimlop::detail
