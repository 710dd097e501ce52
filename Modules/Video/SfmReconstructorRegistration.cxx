#include <vimlop/Video/SfmReconstructor.h>

#include <vimlop/Video/SfmGeometry.h>

#include <opencv2/calib3d.hpp>

namespace vimlop::detail
{

void SfmReconstructor::addObservations(int frame)
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

void SfmReconstructor::registerRemaining()
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

} // namespace vimlop::detail
