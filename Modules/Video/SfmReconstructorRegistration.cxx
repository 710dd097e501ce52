#include <vimlop/Video/SfmReconstructor.h>

#include <vimlop/Video/CameraResection.h>
#include <vimlop/Video/SfmGeometry.h>

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
    std::vector<Eigen::Vector3d> object;
    std::vector<Eigen::Vector2d> image;
    for (const auto& [keypoint, trackIndex] : this->TrackOf[next])
    {
      const int p = this->Tracks[trackIndex].point;
      if (p >= 0 && this->Observations[p].size() >= 2)
      {
        object.push_back(this->Points[p]);
        image.push_back(pixelOf(this->Features[next].keypoints[keypoint]));
      }
    }
    CameraResectionOptions pnp;
    pnp.thresholdPx = this->O.pnpThresholdPx;
    const std::optional<CameraResection> resection = resectCamera(object, image, this->K, pnp);
    const std::size_t inliers = resection ? resection->inliers.size() : 0;
    if (static_cast<int>(inliers) < this->O.minRegistrationPoints)
    {
      failed[next] = true;
      this->say("frame " + std::to_string(next) + ": only " + std::to_string(inliers) +
        " PnP inliers; not registered");
      continue;
    }
    this->Poses[next] = resection->cameraToWorld;
    this->Registered[next] = true;
    this->addObservations(next);
    this->triangulateTracks();
    this->adjust(10);
    this->say("frame " + std::to_string(next) + " registered (" + std::to_string(inliers) +
      " PnP inliers), " + std::to_string(this->Points.size()) + " points");
  }
  this->adjust(100);
}

} // namespace vimlop::detail
