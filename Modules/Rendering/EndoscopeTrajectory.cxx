#include <vimlop/Rendering/EndoscopeTrajectory.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/RandomDirection.h>
#include <vimlop/Core/RayClearance.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/VisibleModelContours.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

namespace vimlop
{

namespace
{

constexpr double Degree = M_PI / 180.0;

bool hasClearance(const RegistrationModel& model, const Eigen::Vector3d& p, double clearanceMm)
{
  return model.isInside(p) && model.locator().closestPoint(p).distanceMm >= clearanceMm;
}

} // namespace

std::vector<CameraPose> makeEndoscopeTrajectory(
  const RegistrationModel& model, const EndoscopeTrajectoryOptions& o, std::uint64_t seed)
{
  if (o.frames < 2 || !(o.stepMm > 0.0) || !(o.minClearanceMm >= 0.0) ||
    !(o.swayAmplitudeMm >= 0.0) || !(o.swayPeriodFrames > 0.0) || o.maxAttempts < 1)
  {
    throw Error("endoscope trajectory: need at least 2 frames, a positive step and sway period, "
                "and non-negative clearance and sway");
  }
  if (o.minContourSamples > 0)
  {
    o.intrinsics.validate();
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Matrix<double, 3, 2> bounds = model.mesh().bounds();
  const double pathLength = (o.frames - 1) * o.stepMm;

  for (int attempt = 0; attempt < o.maxAttempts; ++attempt)
  {
    Eigen::Vector3d start;
    for (int a = 0; a < 3; ++a)
    {
      start[a] = bounds(a, 0) + unit(rng) * (bounds(a, 1) - bounds(a, 0));
    }
    if (!hasClearance(model, start, o.minClearanceMm + o.swayAmplitudeMm))
    {
      continue;
    }
    // The passage axis: among random directions with enough free length, the
    // one that keeps farthest from the walls (least clearance along it), then
    // refined by small turns. A straight path that keeps its distance from
    // the walls runs along the passage, not across it.
    const double needed = pathLength + o.lookAheadMm;
    auto clearanceAlong = [&](const Eigen::Vector3d& d)
    {
      // 0.5 mm steps: the look-ahead beyond the path is short, so a coarser
      // walk would let the camera look at a wall it should have seen.
      if (freeLengthAlongRay(model.tree(), start, d, needed, 0.5) < needed)
      {
        return -1.0;
      }
      double least = std::numeric_limits<double>::infinity();
      for (double t = 0.0; t <= pathLength + 0.5 * o.lookAheadMm; t += 1.0)
      {
        least = std::min(least, model.locator().closestPoint(start + t * d).distanceMm);
      }
      return least;
    };
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    double best = -1.0;
    for (int k = 0; k < 48; ++k)
    {
      const Eigen::Vector3d d = randomDirection(rng);
      const double clearance = clearanceAlong(d);
      if (clearance > best)
      {
        best = clearance;
        axis = d;
      }
    }
    if (best < 0.0)
    {
      continue;
    }
    for (double turn : { 8.0, 4.0, 2.0 })
    {
      for (int k = 0; k < 12; ++k)
      {
        const Eigen::Vector3d d =
          (rotationFromVector(turn * Degree * randomDirection(rng)) * axis).normalized();
        const double clearance = clearanceAlong(d);
        if (clearance > best)
        {
          best = clearance;
          axis = d;
        }
      }
    }
    // Two axes across the passage for the sway, and the image "up".
    Eigen::Vector3d across1 = randomDirection(rng);
    across1 -= across1.dot(axis) * axis;
    if (across1.norm() < 1e-3)
    {
      continue;
    }
    across1.normalize();
    const Eigen::Vector3d across2 = axis.cross(across1);
    const double phase1 = 2.0 * M_PI * unit(rng);
    const double phase2 = 2.0 * M_PI * unit(rng);
    const double phase3 = 2.0 * M_PI * unit(rng);
    const double rollPhase = 2.0 * M_PI * unit(rng);
    // Drawn only when asked for, so that the default paths stay as they were.
    const double rollOffset =
      o.uprightRollDeg >= 0.0 ? (2.0 * unit(rng) - 1.0) * o.uprightRollDeg * Degree : 0.0;

    std::vector<CameraPose> path;
    bool ok = true;
    for (int f = 0; f < o.frames && ok; ++f)
    {
      const double t = 2.0 * M_PI * f / o.swayPeriodFrames;
      // An ellipse-like sway: the two sideways components at incommensurate
      // frequencies, so the tip does not move along a line.
      const Eigen::Vector3d sway = o.swayAmplitudeMm *
        (std::sin(t + phase1) * across1 + 0.7 * std::sin(1.37 * t + phase2) * across2);
      const Eigen::Vector3d centre = start + f * o.stepMm * axis + sway;
      ok = hasClearance(model, centre, o.minClearanceMm);
      const double wobble = o.viewSwayDeg * Degree;
      const Eigen::Vector3d look = (axis + wobble * std::sin(0.8 * t + phase3) * across1 +
        wobble * std::cos(0.6 * t + phase3) * across2)
                                     .normalized();
      // Looking straight up or down, the upright scope's "up" is anterior (-y).
      const Eigen::Vector3d superior = std::abs(look.z()) < 0.95
        ? Eigen::Vector3d(Eigen::Vector3d::UnitZ())
        : Eigen::Vector3d(-Eigen::Vector3d::UnitY());
      const Eigen::Vector3d up =
        rotationFromVector((rollOffset + 0.5 * wobble * std::sin(0.5 * t + rollPhase)) * look) *
        (o.uprightRollDeg >= 0.0 ? superior : across1);
      path.push_back(CameraPose::lookAt(centre, centre + look, up));
    }
    if (!ok)
    {
      continue;
    }
    if (o.minContourSamples > 0)
    {
      for (const CameraPose& pose : path)
      {
        if (static_cast<int>(visibleModelContours(model, o.intrinsics, pose).size()) <
          o.minContourSamples)
        {
          ok = false;
          break;
        }
      }
    }
    if (ok)
    {
      return path;
    }
  }
  char text[256];
  std::snprintf(text, sizeof(text),
    "endoscope trajectory: found no straight passage of %.1f mm with %.1f mm clearance (and "
    "contours in view) in %d attempts",
    pathLength + o.lookAheadMm, o.minClearanceMm, o.maxAttempts);
  throw Error(text);
}

} // namespace vimlop
