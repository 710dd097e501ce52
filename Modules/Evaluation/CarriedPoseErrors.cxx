#include <vimlop/Evaluation/CarriedPoseErrors.h>

#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/SimilarityEstimation.h>
#include <vimlop/Core/Statistics.h>

#include <algorithm>
#include <cmath>

namespace vimlop
{

namespace
{

using Point = std::array<double, 3>;

/// Step (mm) of the frame points.
constexpr double kFrameStepMm = 1.0;

/// Radius (mm) of the walls that turn a pose, and the fewest vertices that do.
constexpr double kWallRadiusMm = 15.0;
constexpr std::size_t kFewestWallVertices = 10;

Eigen::Vector3d vector(const Point& p)
{
  return { p[0], p[1], p[2] };
}

/// The angle (degrees) between two orientations of one camera.
double angleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b)
{
  return rotationAngleBetween(a, b) * 180.0 / M_PI;
}

WallOrientationSummary summarizeAngles(const std::vector<double>& deg)
{
  WallOrientationSummary s;
  s.poses = deg.size();
  if (!deg.empty())
  {
    const Summary summary = summarize(deg);
    s.meanDeg = summary.mean;
    s.p95Deg = summary.p95;
    s.maxDeg = summary.max;
  }
  return s;
}

} // namespace

std::vector<Point> poseFramePoints(const std::vector<CameraPose>& poses)
{
  std::vector<Point> points;
  for (const CameraPose& pose : poses)
  {
    for (int a = -1; a < 3; ++a)
    {
      Eigen::Vector3d p = pose.centre;
      if (a >= 0)
      {
        p[a] += kFrameStepMm;
      }
      points.push_back({ p.x(), p.y(), p.z() });
    }
  }
  return points;
}

std::vector<CameraPose> carriedPoses(
  const std::vector<CameraPose>& poses, const std::vector<Point>& images, std::size_t first)
{
  std::vector<CameraPose> carried;
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    auto image = [&](std::size_t k) { return vector(images[first + 4 * i + k]); };
    Eigen::Matrix3d jacobian;
    for (int a = 0; a < 3; ++a)
    {
      jacobian.col(a) = (image(static_cast<std::size_t>(a) + 1) - image(0)) / kFrameStepMm;
    }
    CameraPose pose;
    pose.centre = image(0);
    pose.rotation = nearestRotation(jacobian) * poses[i].rotation;
    carried.push_back(pose);
  }
  return carried;
}

PoseErrorSummary summarizePoseErrors(const std::vector<CameraPose>& estimate,
  const std::vector<CameraPose>& truth, const std::vector<CameraPose>& templatePoses,
  const RegistrationModel& templateModel)
{
  PoseErrorSummary s;
  s.poses = truth.size();
  if (truth.empty())
  {
    return s;
  }
  std::vector<double> mm(truth.size());
  std::vector<double> deg(truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i)
  {
    mm[i] = cameraPositionError(estimate[i], truth[i]);
    deg[i] = cameraAngleErrorDeg(estimate[i], truth[i]);
  }
  const std::size_t worst =
    static_cast<std::size_t>(std::max_element(deg.begin(), deg.end()) - deg.begin());
  const Eigen::Vector3d at = templatePoses[worst].centre;
  s.maxDegAtMm = { at.x(), at.y(), at.z() };
  s.maxDegWallDistanceMm = templateModel.locator().closestPoint(at).distanceMm;
  const Summary position = summarize(mm);
  const Summary orientation = summarize(deg);
  s.meanMm = position.mean;
  s.p95Mm = position.p95;
  s.maxMm = position.max;
  s.meanDeg = orientation.mean;
  s.p95Deg = orientation.p95;
  s.maxDeg = orientation.max;
  return s;
}

WallOrientations::WallOrientations(const std::vector<CameraPose>& poses,
  const std::vector<Point>& vertices, const std::vector<std::size_t>& scored,
  const std::vector<Point>& truthImages, const std::vector<CameraPose>& truePoses)
  : Poses(poses)
  , Vertices(vertices)
  , Walls(poses.size())
  , TruePoses(truePoses)
{
  for (std::size_t k = 0; k < poses.size(); ++k)
  {
    for (std::size_t i : scored)
    {
      if ((vector(vertices[i]) - poses[k].centre).norm() <= kWallRadiusMm)
      {
        this->Walls[k].push_back(i);
      }
    }
    if (this->Walls[k].size() < kFewestWallVertices)
    {
      this->Walls[k].clear();
    }
  }
  this->TruthTurns = this->turns(truthImages);
}

std::vector<std::optional<Eigen::Matrix3d>> WallOrientations::turns(
  const std::vector<Point>& images) const
{
  std::vector<std::optional<Eigen::Matrix3d>> turned(this->Poses.size());
  for (std::size_t k = 0; k < this->Poses.size(); ++k)
  {
    if (this->Walls[k].empty())
    {
      continue;
    }
    std::vector<Eigen::Vector3d> from, to;
    for (std::size_t i : this->Walls[k])
    {
      from.push_back(vector(this->Vertices[i]));
      to.push_back(vector(images[i]));
    }
    turned[k] = estimateSimilarity(from, to).rotation * this->Poses[k].rotation;
  }
  return turned;
}

WallOrientationSummary WallOrientations::errorsOf(const std::vector<Point>& images) const
{
  const std::vector<std::optional<Eigen::Matrix3d>> turned = this->turns(images);
  std::vector<double> deg;
  for (std::size_t k = 0; k < turned.size(); ++k)
  {
    if (turned[k])
    {
      deg.push_back(angleDeg(*turned[k], *this->TruthTurns[k]));
    }
  }
  return summarizeAngles(deg);
}

WallOrientationSummary WallOrientations::truthAgainstJacobian() const
{
  std::vector<double> deg;
  for (std::size_t k = 0; k < this->TruthTurns.size(); ++k)
  {
    if (this->TruthTurns[k])
    {
      deg.push_back(angleDeg(*this->TruthTurns[k], this->TruePoses[k].rotation));
    }
  }
  return summarizeAngles(deg);
}

} // namespace vimlop
