#include <vimlop/Core/CanonicalPoses.h>

#include <vimlop/Core/Error.h>

#include <Eigen/Geometry>
#include <vimlop/Core/MeshTree.h>
#include <vimlop/Core/RayClearance.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/SurfaceLocator.h>
#include <vimlop/Core/TaskPool.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vimlop
{

namespace
{

constexpr double Degree = M_PI / 180.0;

/// Evenly spread unit vectors (a Fibonacci sphere).
std::vector<Eigen::Vector3d> sphereDirections(int n)
{
  std::vector<Eigen::Vector3d> directions;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double r = std::sqrt(1.0 - z * z);
    directions.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return directions;
}

/// The least wall distance along `length` mm from `p` towards `d`, or -1 when
/// the segment hits the wall.
double clearanceAlong(
  const RegistrationModel& model, const Eigen::Vector3d& p, const Eigen::Vector3d& d, double length)
{
  // One step of the whole length: a view only needs to know whether it is free.
  if (freeLengthAlongRay(model.tree(), p, d, length, length) < length)
  {
    return -1.0;
  }
  double least = std::numeric_limits<double>::infinity();
  for (double t = 1.0; t <= length; t += 1.0)
  {
    least = std::min(least, model.locator().closestPoint(p + t * d).distanceMm);
  }
  return least;
}

/// Turns `look` by shrinking steps towards more clearance: the sphere of
/// directions is sampled about 10 degrees apart, passages are narrower.
Eigen::Vector3d refineView(
  const RegistrationModel& model, const Eigen::Vector3d& p, Eigen::Vector3d look, double length)
{
  double best = clearanceAlong(model, p, look, length);
  for (double stepDeg : { 6.0, 3.0, 1.5, 0.75 })
  {
    const Eigen::Vector3d helper =
      std::abs(look.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d a = look.cross(helper).normalized();
    const Eigen::Vector3d b = look.cross(a);
    for (const Eigen::Vector3d& axis : { a, Eigen::Vector3d(-a), b, Eigen::Vector3d(-b) })
    {
      const Eigen::Vector3d turned = rotationFromVector(stepDeg * Degree * axis) * look;
      const double clearance = clearanceAlong(model, p, turned, length);
      if (clearance > best)
      {
        best = clearance;
        look = turned.normalized();
      }
    }
  }
  return look;
}

} // namespace

void CanonicalPoseOptions::validate() const
{
  if (!(this->spacingMm > 0.0) || !(this->minClearanceMm >= 0.0) || !(this->lookAheadMm > 0.0))
  {
    throw Error("canonical poses: spacing and look-ahead must be positive and clearance not "
                "negative");
  }
  if (this->viewsPerPosition < 1 || this->rollsDeg.empty() || this->maxPoses < 1)
  {
    throw Error("canonical poses: need at least one view per position, one roll and one pose");
  }
  if (this->threads < 0)
  {
    throw Error("canonical poses: the thread count must not be negative");
  }
  if (!(this->upCT.norm() > 0.0) || !this->upCT.allFinite())
  {
    throw Error("canonical poses: the up direction must be a non-zero vector");
  }
}

std::vector<CameraPose> makeCanonicalPoses(
  const RegistrationModel& model, const CanonicalPoseOptions& o)
{
  o.validate();
  // Grid points inside the airway with enough clearance, at half the spacing.
  const Eigen::Matrix<double, 3, 2> bounds = model.mesh().bounds();
  const double step = 0.5 * o.spacingMm;
  struct Site
  {
    Eigen::Vector3d position;
    double clearanceMm;
  };
  // Each slice of the grid, and below each position, is one task; their
  // results are joined in order, so the poses do not depend on the threads.
  TaskPool pool(o.threads);
  std::vector<double> slices;
  for (double z = bounds(2, 0) + step; z < bounds(2, 1); z += step)
  {
    slices.push_back(z);
  }
  std::vector<std::vector<Site>> sitesOfSlice(slices.size());
  pool.run(static_cast<int>(slices.size()),
    [&](int k)
    {
      for (double y = bounds(1, 0) + step; y < bounds(1, 1); y += step)
      {
        for (double x = bounds(0, 0) + step; x < bounds(0, 1); x += step)
        {
          const Eigen::Vector3d p(x, y, slices[k]);
          if (!model.isInside(p))
          {
            continue;
          }
          const double clearance = model.locator().closestPoint(p).distanceMm;
          if (clearance >= o.minClearanceMm)
          {
            sitesOfSlice[k].push_back({ p, clearance });
          }
        }
      }
    });
  std::vector<Site> sites;
  for (const std::vector<Site>& slice : sitesOfSlice)
  {
    sites.insert(sites.end(), slice.begin(), slice.end());
  }
  if (sites.empty())
  {
    throw Error("canonical poses: no point of the airway is " + std::to_string(o.minClearanceMm) +
      " mm from the wall");
  }
  // The deepest first (stable: grid order breaks ties), then every site
  // farther than the spacing from those taken.
  std::stable_sort(sites.begin(), sites.end(),
    [](const Site& a, const Site& b) { return a.clearanceMm > b.clearanceMm; });
  std::vector<Eigen::Vector3d> positions;
  for (const Site& s : sites)
  {
    bool farEnough = true;
    for (const Eigen::Vector3d& p : positions)
    {
      if ((p - s.position).squaredNorm() < o.spacingMm * o.spacingMm)
      {
        farEnough = false;
        break;
      }
    }
    if (farEnough)
    {
      positions.push_back(s.position);
    }
  }

  const std::vector<Eigen::Vector3d> directions = sphereDirections(400);
  const double separation = std::cos(o.minViewSeparationDeg * Degree);
  const Eigen::Vector3d up = o.upCT.normalized();
  std::vector<std::vector<CameraPose>> posesAt(positions.size());
  pool.run(static_cast<int>(positions.size()),
    [&](int k)
    {
      const Eigen::Vector3d& p = positions[k];
      std::vector<std::pair<double, int>> open;
      for (size_t d = 0; d < directions.size(); ++d)
      {
        const double clearance = clearanceAlong(model, p, directions[d], o.lookAheadMm);
        if (clearance > 0.0)
        {
          open.emplace_back(-clearance, static_cast<int>(d));
        }
      }
      std::sort(open.begin(), open.end());
      std::vector<Eigen::Vector3d> views;
      for (const auto& [negativeClearance, d] : open)
      {
        const Eigen::Vector3d& v = directions[d];
        if (std::all_of(
              views.begin(), views.end(), [&](const auto& w) { return v.dot(w) < separation; }))
        {
          views.push_back(v);
          if (static_cast<int>(views.size()) == o.viewsPerPosition)
          {
            break;
          }
        }
      }
      for (Eigen::Vector3d look : views)
      {
        look = refineView(model, p, look, o.lookAheadMm);
        // Looking straight up or down, "up" is the anterior (-y in LPS).
        const Eigen::Vector3d hint =
          std::abs(look.dot(up)) < 0.95 ? up : Eigen::Vector3d(-Eigen::Vector3d::UnitY());
        const CameraPose upright = CameraPose::lookAt(p, p + look, hint);
        for (double roll : o.rollsDeg)
        {
          CameraPose pose = upright;
          pose.rotation = rotationFromVector(roll * Degree * look) * upright.rotation;
          posesAt[k].push_back(pose);
        }
      }
    });
  std::vector<CameraPose> poses;
  for (const std::vector<CameraPose>& at : posesAt)
  {
    for (const CameraPose& pose : at)
    {
      if (static_cast<int>(poses.size()) == o.maxPoses)
      {
        return poses;
      }
      poses.push_back(pose);
    }
  }
  return poses;
}

} // namespace vimlop
