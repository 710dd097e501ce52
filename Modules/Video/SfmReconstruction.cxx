#include <vimlop/Video/SfmReconstruction.h>

#include <vimlop/Core/Error.h>

#include <Eigen/Dense>

#include <cmath>
#include <map>

namespace vimlop
{

int SfmReconstruction::numberOfRegisteredFrames() const
{
  int n = 0;
  for (const Frame& f : this->frames)
  {
    n += f.registered;
  }
  return n;
}

double SfmReconstruction::rmsReprojectionErrorPx() const
{
  double sum = 0.0;
  long count = 0;
  for (const Point& p : this->points)
  {
    for (const Observation& o : p.observations)
    {
      // A reconstruction that fails validate() (a dangling frame index) may
      // still be written, e.g. to show a problem; its error must not read
      // past the frames (found by AddressSanitizer).
      if (o.frame < 0 || o.frame >= static_cast<int>(this->frames.size()))
      {
        continue;
      }
      const Frame& f = this->frames[static_cast<size_t>(o.frame)];
      const Eigen::Vector3d x = f.cameraToSfm.worldToCamera(p.position);
      if (x.z() <= 0.0)
      {
        continue;
      }
      sum += (f.intrinsics.project(x) - o.pixel).squaredNorm();
      ++count;
    }
  }
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}

Eigen::Matrix3d SfmReconstruction::triangulationCovariance(const Eigen::Vector3d& position,
  const std::vector<Observation>& observations, double sigmaPx) const
{
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  double depthSum = 0.0;
  for (const Observation& o : observations)
  {
    const Frame& f = this->frames[static_cast<size_t>(o.frame)];
    const Eigen::Vector3d x = f.cameraToSfm.worldToCamera(position);
    if (x.z() <= 0.0)
    {
      continue;
    }
    depthSum += x.z();
    // d pixel / d camera point, then d camera point / d world point = R^T.
    Eigen::Matrix<double, 2, 3> j;
    j << f.intrinsics.fx / x.z(), 0.0, -f.intrinsics.fx * x.x() / (x.z() * x.z()), 0.0,
      f.intrinsics.fy / x.z(), -f.intrinsics.fy * x.y() / (x.z() * x.z());
    const Eigen::Matrix<double, 2, 3> jw = j * f.cameraToSfm.rotation.transpose();
    information += jw.transpose() * jw;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(information);
  const double largest = eigen.eigenvalues().maxCoeff();
  if (!(largest > 0.0) || eigen.eigenvalues().minCoeff() < 1e-10 * largest)
  {
    // No depth information: as uncertain as the point is far.
    const double depth = depthSum > 0.0 ? depthSum / observations.size() : 1.0;
    return depth * depth * Eigen::Matrix3d::Identity();
  }
  return sigmaPx * sigmaPx * information.inverse();
}

void SfmReconstruction::computeCovariances(double sigmaPx)
{
  for (Point& p : this->points)
  {
    p.covariance = this->triangulationCovariance(p.position, p.observations, sigmaPx);
    double sum = 0.0;
    int count = 0;
    for (const Observation& o : p.observations)
    {
      const Frame& f = this->frames[static_cast<size_t>(o.frame)];
      const Eigen::Vector3d x = f.cameraToSfm.worldToCamera(p.position);
      if (x.z() > 0.0)
      {
        sum += (f.intrinsics.project(x) - o.pixel).squaredNorm();
        ++count;
      }
    }
    p.reprojectionErrorPx = count > 0 ? std::sqrt(sum / count) : 0.0;
  }
}

void SfmReconstruction::validate() const
{
  for (size_t i = 0; i < this->points.size(); ++i)
  {
    const Point& p = this->points[i];
    if (!p.position.allFinite() || !p.covariance.allFinite())
    {
      throw Error("SfM point " + std::to_string(i) + " has a non-finite position or covariance");
    }
    for (const Observation& o : p.observations)
    {
      if (o.frame < 0 || o.frame >= static_cast<int>(this->frames.size()))
      {
        throw Error("SfM point " + std::to_string(i) + " is observed by frame " +
          std::to_string(o.frame) + ", which does not exist");
      }
      if (!this->frames[static_cast<size_t>(o.frame)].registered)
      {
        throw Error("SfM point " + std::to_string(i) + " is observed by frame '" +
          this->frames[static_cast<size_t>(o.frame)].name + "', which is not registered");
      }
    }
  }
  for (const Frame& f : this->frames)
  {
    if (f.registered && (!f.cameraToSfm.centre.allFinite() || !f.cameraToSfm.rotation.allFinite()))
    {
      throw Error("SfM frame '" + f.name + "' has a non-finite pose");
    }
  }
}

SfmReconstruction SfmReconstruction::forFrames(
  const std::vector<std::string>& names, std::vector<std::string>* warnings) const
{
  SfmReconstruction r;
  r.source = this->source;
  r.trackerScale = this->trackerScale;
  std::map<std::string, int> frameOfName;
  for (size_t f = 0; f < names.size(); ++f)
  {
    frameOfName[names[f]] = static_cast<int>(f);
    SfmReconstruction::Frame frame;
    frame.name = names[f];
    r.frames.push_back(frame);
  }
  std::vector<int> newIndex(this->frames.size(), -1);
  std::vector<std::string> notNamed;
  for (size_t f = 0; f < this->frames.size(); ++f)
  {
    const auto at = frameOfName.find(this->frames[f].name);
    if (at == frameOfName.end())
    {
      notNamed.push_back(this->frames[f].name);
      continue;
    }
    newIndex[f] = at->second;
    r.frames[static_cast<size_t>(at->second)] = this->frames[f];
  }
  int droppedPoints = 0;
  for (const Point& point : this->points)
  {
    Point kept = point;
    kept.observations.clear();
    for (const Observation& o : point.observations)
    {
      if (o.frame >= 0 && static_cast<size_t>(o.frame) < newIndex.size() && newIndex[o.frame] >= 0)
      {
        kept.observations.push_back({ newIndex[o.frame], o.pixel });
      }
    }
    if (kept.observations.size() < 2)
    {
      ++droppedPoints;
      continue;
    }
    r.points.push_back(std::move(kept));
  }
  if (warnings)
  {
    if (!notNamed.empty())
    {
      warnings->push_back("SfM: dropped " + std::to_string(notNamed.size()) +
        " frame(s) not among the frames (first: '" + notNamed.front() + "') and " +
        std::to_string(droppedPoints) + " point(s) seen in fewer than 2 of the others");
    }
    for (const Frame& f : r.frames)
    {
      if (!f.registered)
      {
        warnings->push_back("SfM: frame '" + f.name + "' is not registered");
      }
    }
  }
  return r;
}

} // namespace vimlop
