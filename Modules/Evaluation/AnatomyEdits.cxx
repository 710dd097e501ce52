#include <vimlop/Evaluation/AnatomyEdits.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

#include <algorithm>
#include <cmath>
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
  // Draws until there are enough edits or a budget of draws is spent.
  for (int draw = 0; draw < 1000 && static_cast<int>(edits.size()) < options.count; ++draw)
  {
    const std::array<double, 3>& p = wallPointsMm[generator() % wallPointsMm.size()];
    const bool free = std::all_of(edits.begin(), edits.end(),
      [&](const AnatomyEdit& e) { return distance(e.centreMm, p) >= apart; });
    if (free)
    {
      edits.push_back({ kinds[edits.size() % 3], p });
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
