#include <vimlop/Rendering/EndoscopeTrajectory.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/RandomDirection.h>
#include <vimlop/Core/RayClearance.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Core/VisibleModelContours.h>

#include <Eigen/Geometry>

#include <cmath>
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

void requireFiniteNonNegative(double value, const char* what, const char* unit)
{
  if (!(value >= 0.0 && std::isfinite(value)))
  {
    throw Error(formatText(
      "endoscope trajectory: the %s must be a finite number >= 0 %s, not %g", what, unit, value));
  }
}

/// The axis of a curved path: an arc from `start` along `direction`, turning
/// toward `bend` (a unit vector across `direction`) by `curvatureRadPerMm`.
struct ArcAxis
{
  Eigen::Vector3d start;
  Eigen::Vector3d direction;
  Eigen::Vector3d bend;
  double curvatureRadPerMm = 0.0;

  /// The point `s` mm along the arc.
  Eigen::Vector3d point(double s) const
  {
    const double a = this->curvatureRadPerMm * s;
    return this->start +
      (std::sin(a) * this->direction + (1.0 - std::cos(a)) * this->bend) / this->curvatureRadPerMm;
  }
  /// The rotation that carries the start's tangent (and frame) to the tangent at `s`.
  Eigen::Matrix3d turn(double s) const
  {
    return rotationFromVector(this->curvatureRadPerMm * s * this->direction.cross(this->bend));
  }
};

/// `v` made perpendicular to the unit vector `axis` and unit; zero when nearly parallel.
Eigen::Vector3d across(const Eigen::Vector3d& v, const Eigen::Vector3d& axis)
{
  const Eigen::Vector3d w = v - v.dot(axis) * axis;
  return w.norm() < 1e-3 ? Eigen::Vector3d(Eigen::Vector3d::Zero())
                         : Eigen::Vector3d(w.normalized());
}

} // namespace

void EndoscopeTrajectoryOptions::validate() const
{
  if (this->frames < 2 || !(this->stepMm > 0.0) || !(this->minClearanceMm >= 0.0) ||
    !(this->swayAmplitudeMm >= 0.0) || !(this->swayPeriodFrames > 0.0) || this->maxAttempts < 1)
  {
    throw Error("endoscope trajectory: need at least 2 frames, a positive step and sway period, "
                "and non-negative clearance and sway");
  }
  requireFiniteNonNegative(this->jitterMm, "position jitter", "mm");
  requireFiniteNonNegative(this->jitterDeg, "view jitter", "degrees");
  requireFiniteNonNegative(this->turnDegPerMm, "turn of the path", "degrees per mm");
}

std::vector<CameraPose> makeEndoscopeTrajectory(
  const RegistrationModel& model, const EndoscopeTrajectoryOptions& o, std::uint64_t seed)
{
  o.validate();
  if (o.minContourSamples > 0)
  {
    o.intrinsics.validate();
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Matrix<double, 3, 2> bounds = model.mesh().bounds();
  const double pathLength = (o.frames - 1) * o.stepMm;
  const bool curved = o.turnDegPerMm > 0.0;
  // The tremor has its own generator, drawn only when asked for, so that the
  // smooth path (and the default one) stays as it was.
  std::mt19937_64 tremorRng(seed * 0x9E3779B97F4A7C15ull + 0x7F4A7C15ull);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  auto gaussianVector = [&]
  { return Eigen::Vector3d(gaussian(tremorRng), gaussian(tremorRng), gaussian(tremorRng)); };

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
    // A curved path: the arc and its look-ahead inside, away from the walls
    // at every 0.5 mm (closer than 0.25 mm between two samples would be a
    // crossing); its least clearance along the path is the score, as above.
    ArcAxis arc{ start, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), o.turnDegPerMm * Degree };
    auto clearanceAlongArc = [&](const Eigen::Vector3d& d, const Eigen::Vector3d& bend)
    {
      if (bend.isZero(0.0))
      {
        return -1.0;
      }
      const ArcAxis candidate{ start, d, bend, arc.curvatureRadPerMm };
      double least = std::numeric_limits<double>::infinity();
      for (double t = 0.0; t <= needed; t += 0.5)
      {
        const Eigen::Vector3d q = candidate.point(t);
        const double distance = model.locator().closestPoint(q).distanceMm;
        if (distance < 0.25 || !model.isInside(q))
        {
          return -1.0;
        }
        if (t <= pathLength + 0.5 * o.lookAheadMm)
        {
          least = std::min(least, distance);
        }
      }
      return least;
    };
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    double best = -1.0;
    for (int k = 0; k < 48 && curved; ++k)
    {
      const Eigen::Vector3d d = randomDirection(rng);
      const Eigen::Vector3d bend = across(randomDirection(rng), d);
      const double clearance = clearanceAlongArc(d, bend);
      if (clearance > best)
      {
        best = clearance;
        axis = d;
        arc.bend = bend;
      }
    }
    for (int k = 0; k < 48 && !curved; ++k)
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
        if (curved)
        {
          // The bend turned as much, so that the arc can follow the passage.
          const Eigen::Vector3d bend =
            across(rotationFromVector(turn * Degree * randomDirection(rng)) * arc.bend, d);
          const double clearance = clearanceAlongArc(d, bend);
          if (clearance > best)
          {
            best = clearance;
            axis = d;
            arc.bend = bend;
          }
          continue;
        }
        const double clearance = clearanceAlong(d);
        if (clearance > best)
        {
          best = clearance;
          axis = d;
        }
      }
    }
    arc.direction = axis;
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
      // On a curved path, the sway and the view turn with the axis.
      const Eigen::Matrix3d turn =
        curved ? arc.turn(f * o.stepMm) : Eigen::Matrix3d(Eigen::Matrix3d::Identity());
      Eigen::Vector3d centre = curved ? Eigen::Vector3d(arc.point(f * o.stepMm) + turn * sway)
                                      : Eigen::Vector3d(start + f * o.stepMm * axis + sway);
      if (o.jitterMm > 0.0)
      {
        // Isotropic: each axis gets 1/sqrt(3) of the mean square length.
        centre += o.jitterMm / std::sqrt(3.0) * gaussianVector();
      }
      ok = hasClearance(model, centre, o.minClearanceMm);
      const double wobble = o.viewSwayDeg * Degree;
      Eigen::Vector3d look = (axis + wobble * std::sin(0.8 * t + phase3) * across1 +
        wobble * std::cos(0.6 * t + phase3) * across2)
                               .normalized();
      if (curved)
      {
        look = turn * look;
      }
      // Looking straight up or down, the upright scope's "up" is anterior (-y).
      const Eigen::Vector3d superior = std::abs(look.z()) < 0.95
        ? Eigen::Vector3d(Eigen::Vector3d::UnitZ())
        : Eigen::Vector3d(-Eigen::Vector3d::UnitY());
      const Eigen::Vector3d up =
        rotationFromVector((rollOffset + 0.5 * wobble * std::sin(0.5 * t + rollPhase)) * look) *
        (o.uprightRollDeg >= 0.0 ? superior : (curved ? Eigen::Vector3d(turn * across1) : across1));
      path.push_back(CameraPose::lookAt(centre, centre + look, up));
      if (o.jitterDeg > 0.0)
      {
        // Turned about the camera's own axes: the tremor of the hand holding it.
        path.back().rotation = path.back().rotation *
          rotationFromVector(o.jitterDeg * Degree / std::sqrt(3.0) * gaussianVector());
      }
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
  const std::string passage = curved ? formatText("passage turning %g deg/mm", o.turnDegPerMm)
                                     : std::string("straight passage");
  throw Error(formatText("endoscope trajectory: found no %s of %.1f mm with %.1f mm clearance (and "
                         "contours in view) in %d attempts",
    passage.c_str(), pathLength + o.lookAheadMm, o.minClearanceMm, o.maxAttempts));
}

} // namespace vimlop
