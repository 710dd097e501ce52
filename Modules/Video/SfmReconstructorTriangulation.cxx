#include <vimlop/Video/SfmReconstructor.h>

#include <vimlop/Video/SfmGeometry.h>

#include <algorithm>
#include <cmath>

namespace vimlop::detail
{

Eigen::Vector2d SfmReconstructor::normalised(const Eigen::Vector2d& pixel) const
{
  return { (pixel.x() - this->K.cx) / this->K.fx, (pixel.y() - this->K.cy) / this->K.fy };
}

void SfmReconstructor::triangulateTracks()
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

} // namespace vimlop::detail
