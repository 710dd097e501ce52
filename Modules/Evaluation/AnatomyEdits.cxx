#include <vimlop/Evaluation/AnatomyEdits.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/NasalCavityRegion.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <utility>

namespace vimlop
{

namespace
{

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

/// Draws a candidate with the generator until one lies at least `apart` from
/// every edit so far (a budget of 1000 draws); false when none did.
bool drawApart(const std::vector<std::array<double, 3>>& candidates, std::mt19937& generator,
  const std::vector<AnatomyEdit>& edits, double apart, std::array<double, 3>& drawn)
{
  for (int draw = 0; draw < 1000 && !candidates.empty(); ++draw)
  {
    const std::array<double, 3>& p = candidates[generator() % candidates.size()];
    if (std::all_of(edits.begin(), edits.end(),
          [&](const AnatomyEdit& e) { return distance(e.centreMm, p) >= apart; }))
    {
      drawn = p;
      return true;
    }
  }
  return false;
}

std::array<double, 3> asArray(const Eigen::Vector3d& v)
{
  return { v.x(), v.y(), v.z() };
}

/// The septum's plane x = c: where most near-sagittal vertices lie within
/// `halfWidthMm` and face away from it (0.25 mm steps over the vertices' span).
double septumPlaneX(const std::vector<Eigen::Vector3d>& points,
  const std::vector<Eigen::Vector3d>& normals, double halfWidthMm)
{
  double low = 1e300, high = -1e300;
  for (const Eigen::Vector3d& p : points)
  {
    low = std::min(low, p.x());
    high = std::max(high, p.x());
  }
  double best = 0.5 * (low + high);
  std::size_t bestCount = 0;
  for (double c = low; c <= high; c += 0.25)
  {
    std::size_t count = 0;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      const double off = points[i].x() - c;
      count += std::abs(off) <= halfWidthMm && off * normals[i].x() > 0.0 ? 1 : 0;
    }
    if (count > bestCount)
    {
      bestCount = count;
      best = c;
    }
  }
  return best;
}

/// The lowest air point of `ct` 12-35 mm to the `side` (+1 left, -1 right)
/// of the septum, in the nasal cavity's length and height or up to 10 mm
/// below it (a maxillary sinus's floor lies below the nasal floor), with air
/// 4 mm away along each axis (a large air space, not a cell) and tissue
/// along each axis before the volume's edge (inside the head, not the air
/// in front of the cheek); none when there is no such point.
std::optional<std::array<double, 3>> sinusFloor(const CTVolume& ct, double airThresholdHU,
  const NasalCavityRegion& nose, double septumX, double side)
{
  const auto voxel = [&](const std::array<double, 3>& pointMm, std::array<int, 3>& at)
  {
    const std::array<double, 3> index = ct.physicalToIndex(pointMm);
    for (int a = 0; a < 3; ++a)
    {
      at[a] = static_cast<int>(std::lround(index[a]));
      if (at[a] < 0 || at[a] >= ct.dims[a])
      {
        return false;
      }
    }
    return true;
  };
  const auto isAir = [&](const std::array<int, 3>& at)
  {
    const std::size_t n = static_cast<std::size_t>(at[0]) +
      static_cast<std::size_t>(ct.dims[0]) * (at[1] + static_cast<std::size_t>(ct.dims[1]) * at[2]);
    return ct.intensities[n] < airThresholdHU;
  };
  const auto airAt = [&](const std::array<double, 3>& pointMm)
  {
    std::array<int, 3> at{};
    return voxel(pointMm, at) && isAir(at);
  };
  // Tissue along each index axis, both ways, before the volume's edge.
  const auto enclosed = [&](std::array<int, 3> at)
  {
    for (int a = 0; a < 3; ++a)
    {
      for (int step : { -1, 1 })
      {
        std::array<int, 3> q = at;
        do
        {
          q[a] += step;
        } while (q[a] >= 0 && q[a] < ct.dims[a] && isAir(q));
        if (q[a] < 0 || q[a] >= ct.dims[a])
        {
          return false;
        }
      }
    }
    return true;
  };
  constexpr double probeMm = 4.0;
  std::optional<std::array<double, 3>> lowest;
  for (int k = 0; k < ct.dims[2]; ++k)
  {
    for (int j = 0; j < ct.dims[1]; ++j)
    {
      for (int i = 0; i < ct.dims[0]; ++i)
      {
        const std::array<double, 3> p = ct.indexToPhysical({ double(i), double(j), double(k) });
        const double out = (p[0] - septumX) * side;
        if (out < 12.0 || out > 35.0 || p[1] < nose.yFrontMm || p[1] > nose.yBackMm ||
          p[2] < nose.zLowMm - 10.0 || p[2] > nose.zHighMm || (lowest && p[2] >= (*lowest)[2]) ||
          !isAir({ i, j, k }))
        {
          continue;
        }
        bool deep = true;
        for (int a = 0; a < 3 && deep; ++a)
        {
          for (double sign : { -1.0, 1.0 })
          {
            std::array<double, 3> q = p;
            q[a] += sign * probeMm;
            deep = deep && airAt(q);
          }
        }
        if (deep && enclosed({ i, j, k }))
        {
          lowest = p;
        }
      }
    }
  }
  return lowest;
}

} // namespace

std::string anatomyEditKindName(AnatomyEditKind kind)
{
  switch (kind)
  {
    case AnatomyEditKind::ShrinkTissue:
      return "shrink";
    case AnatomyEditKind::FillAir:
      return "fill";
    case AnatomyEditKind::GrowTissue:
      break;
  }
  return "grow";
}

void AnatomyEditOptions::validate() const
{
  auto check = [](bool ok, const char* what, double value)
  {
    if (!ok)
    {
      throw Error(formatText("anatomy edits: %s %g is out of range", what, value));
    }
  };
  check(count >= 0 && count <= 20, "count (0-20)", count);
  if (placement == AnatomyEditPlacement::AnatomicalSites && count > 4)
  {
    throw Error(
      formatText("anatomy edits: the anatomical sites hold at most 4 edits, not %d", count));
  }
  check(radiusMm >= 1.0 && radiusMm <= 20.0, "radius (1-20 mm)", radiusMm);
  check(depthMm >= 0.5 && depthMm <= 5.0, "depth (0.5-5 mm)", depthMm);
}

std::vector<AnatomyEdit> placeAnatomyEdits(
  const std::vector<std::array<double, 3>>& wallPointsMm, const AnatomyEditOptions& options)
{
  options.validate();
  std::vector<AnatomyEdit> edits;
  if (wallPointsMm.empty())
  {
    return edits;
  }
  const double apart = 2.0 * (options.radiusMm + options.depthMm);
  std::mt19937 generator(options.seed);
  const AnatomyEditKind kinds[3] = { AnatomyEditKind::GrowTissue, AnatomyEditKind::ShrinkTissue,
    AnatomyEditKind::FillAir };
  std::array<double, 3> p{};
  while (static_cast<int>(edits.size()) < options.count &&
    drawApart(wallPointsMm, generator, edits, apart, p))
  {
    edits.push_back({ kinds[edits.size() % 3], p });
  }
  return edits;
}

std::vector<AnatomyEdit> placeAnatomicalEdits(
  const TriangleMesh& airway, const CTVolume& ct, const AnatomyEditOptions& options)
{
  options.validate();
  const NasalCavityRegion nose = NasalCavityRegion::inBounds(airway.bounds());
  // The nasal cavity's near-sagittal wall vertices.
  std::vector<Eigen::Vector3d> points, normals;
  for (std::size_t i = 0; i < airway.vertices().size(); ++i)
  {
    const Eigen::Vector3d& n = airway.vertexNormals()[i];
    if (nose.contains(airway.vertices()[i]) && std::abs(n.x()) > 0.7)
    {
      points.push_back(airway.vertices()[i]);
      normals.push_back(n);
    }
  }
  if (points.empty())
  {
    throw Error("anatomical edits: the airway has no near-sagittal walls in the nasal cavity "
                "(is it a nasal airway in the CT frame, LPS?)");
  }
  constexpr double septumHalfWidthMm = 3.0;
  // The turbinates' medial faces lie 4-12 mm from the septum; farther out
  // are the meatuses and the sinuses.
  constexpr double turbinateNearMm = 4.0;
  constexpr double turbinateFarMm = 12.0;
  const double septumX = septumPlaneX(points, normals, septumHalfWidthMm);
  const double midHeight = 0.5 * (nose.zLowMm + nose.zHighMm);
  // The turbinates begin behind the vestibule, the front fifth of the cavity.
  const double behindVestibule = nose.yFrontMm + 0.2 * (nose.yBackMm - nose.yFrontMm);
  std::mt19937 generator(options.seed);
  // The deviation's side: -1 right (-x), +1 left.
  const double side = generator() % 2 == 0 ? -1.0 : 1.0;
  std::vector<std::array<double, 3>> septum, inferior, middle;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const double off = points[i].x() - septumX;
    const bool facesAway = off * normals[i].x() > 0.0;
    if (std::abs(off) <= septumHalfWidthMm && facesAway && off * side > 0.0)
    {
      septum.push_back(asArray(points[i]));
    }
    else if (std::abs(off) > turbinateNearMm && std::abs(off) <= turbinateFarMm && !facesAway &&
      points[i].y() > behindVestibule)
    {
      const bool low = points[i].z() < midHeight;
      if (low && off * side < 0.0)
      {
        inferior.push_back(asArray(points[i]));
      }
      else if (!low && off * side > 0.0)
      {
        middle.push_back(asArray(points[i]));
      }
    }
  }
  // The maxillary sinus beside the other passage (a scan of the whole CT:
  // only when its edit is asked for).
  std::vector<std::array<double, 3>> sinus;
  const auto floor = options.count >= 4
    ? sinusFloor(ct, options.airThresholdHU, nose, septumX, -side)
    : std::nullopt;
  if (floor)
  {
    sinus.push_back(*floor);
  }
  const struct
  {
    const char* name;
    AnatomyEditKind kind;
    const std::vector<std::array<double, 3>>& candidates;
  } sites[4] = { { "septum", AnatomyEditKind::GrowTissue, septum },
    { "inferior turbinate", AnatomyEditKind::GrowTissue, inferior },
    { "middle turbinate", AnatomyEditKind::ShrinkTissue, middle },
    { "maxillary sinus", AnatomyEditKind::FillAir, sinus } };
  const double apart = 2.0 * (options.radiusMm + options.depthMm);
  std::vector<AnatomyEdit> edits;
  std::array<double, 3> p{};
  for (int s = 0; s < options.count; ++s)
  {
    if (drawApart(sites[s].candidates, generator, edits, apart, p))
    {
      edits.push_back({ sites[s].kind, p, sites[s].name });
    }
  }
  return edits;
}

std::size_t applyAnatomyEdits(
  CTVolume& ct, const std::vector<AnatomyEdit>& edits, const AnatomyEditOptions& options)
{
  options.validate();
  const std::array<int, 3> d = ct.dims;
  auto at = [&](int i, int j, int k)
  {
    return static_cast<std::size_t>(i) +
      static_cast<std::size_t>(d[0]) * (j + static_cast<std::size_t>(d[1]) * k);
  };
  std::size_t changed = 0;
  for (const AnatomyEdit& edit : edits)
  {
    // The sphere's box in voxels, and the neighbourhood that reaches `depthMm`.
    const std::array<double, 3> centre = ct.physicalToIndex(edit.centreMm);
    std::array<int, 3> low{}, high{}, reach{};
    for (int a = 0; a < 3; ++a)
    {
      const double r = options.radiusMm / ct.spacingMm[a];
      low[a] = std::max(0, static_cast<int>(std::floor(centre[a] - r)));
      high[a] = std::min(d[a] - 1, static_cast<int>(std::ceil(centre[a] + r)));
      reach[a] = static_cast<int>(std::ceil(options.depthMm / ct.spacingMm[a]));
    }
    // Decided on the volume before this edit, applied after.
    auto isAir = [&](std::size_t n) { return ct.intensities[n] < options.airThresholdHU; };
    std::vector<std::pair<std::size_t, float>> changes;
    // True when a voxel of the other class lies within `depthMm`.
    auto otherWithinDepth = [&](int i, int j, int k, bool air)
    {
      for (int dk = -reach[2]; dk <= reach[2]; ++dk)
      {
        for (int dj = -reach[1]; dj <= reach[1]; ++dj)
        {
          for (int di = -reach[0]; di <= reach[0]; ++di)
          {
            const int ii = i + di, jj = j + dj, kk = k + dk;
            if (ii < 0 || jj < 0 || kk < 0 || ii >= d[0] || jj >= d[1] || kk >= d[2])
            {
              continue;
            }
            const double mm =
              std::hypot(di * ct.spacingMm[0], dj * ct.spacingMm[1], dk * ct.spacingMm[2]);
            if (mm <= options.depthMm && isAir(at(ii, jj, kk)) != air)
            {
              return true;
            }
          }
        }
      }
      return false;
    };
    for (int k = low[2]; k <= high[2]; ++k)
    {
      for (int j = low[1]; j <= high[1]; ++j)
      {
        for (int i = low[0]; i <= high[0]; ++i)
        {
          if (distance(ct.indexToPhysical({ double(i), double(j), double(k) }), edit.centreMm) >
            options.radiusMm)
          {
            continue;
          }
          const std::size_t n = at(i, j, k);
          const bool air = isAir(n);
          float value = ct.intensities[n];
          switch (edit.kind)
          {
            case AnatomyEditKind::GrowTissue:
              value = air && otherWithinDepth(i, j, k, true) ? float(options.tissueHU) : value;
              break;
            case AnatomyEditKind::ShrinkTissue:
              value = !air && otherWithinDepth(i, j, k, false) ? -1000.0f : value;
              break;
            case AnatomyEditKind::FillAir:
              value = air ? float(options.tissueHU) : value;
              break;
          }
          if (value != ct.intensities[n])
          {
            changes.emplace_back(n, value);
          }
        }
      }
    }
    for (const auto& [n, value] : changes)
    {
      ct.intensities[n] = value;
    }
    changed += changes.size();
  }
  return changed;
}

bool nearAnatomyEdit(const std::array<double, 3>& pointMm, const std::vector<AnatomyEdit>& edits,
  const AnatomyEditOptions& options)
{
  return std::any_of(edits.begin(), edits.end(),
    [&](const AnatomyEdit& e)
    { return distance(e.centreMm, pointMm) <= options.radiusMm + options.depthMm; });
}

} // namespace vimlop
