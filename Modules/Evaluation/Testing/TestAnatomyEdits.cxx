// Local edits of the anatomy for P4's harder pairs, on a slab of air against
// tissue made in memory.
#include "ErrorMessage.h"
#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/AnatomyEdits.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

using namespace vimlop;
using vimlop::fixtures::makeBox;
using vimlop::fixtures::merge;

namespace
{

/// 60^3 voxels of 0.5 mm: air (-1000 HU) where x < 15 mm, tissue (40 HU) beyond.
CTVolume airAgainstTissue()
{
  CTVolume v;
  v.dims = { 60, 60, 60 };
  v.spacingMm = { 0.5, 0.5, 0.5 };
  v.intensities.resize(v.numberOfVoxels());
  std::size_t n = 0;
  for (int k = 0; k < 60; ++k)
  {
    for (int j = 0; j < 60; ++j)
    {
      for (int i = 0; i < 60; ++i, ++n)
      {
        v.intensities[n] = i * 0.5 < 15.0 ? -1000.0f : 40.0f;
      }
    }
  }
  return v;
}

float valueAt(const CTVolume& v, const std::array<double, 3>& pointMm)
{
  const std::array<double, 3> index = v.physicalToIndex(pointMm);
  return v.intensities[static_cast<std::size_t>(index[0]) +
    60 * (static_cast<std::size_t>(index[1]) + 60 * static_cast<std::size_t>(index[2]))];
}

} // namespace

TEST(AnatomyEdits, GrowShrinkAndFillChangeTheWallInsideTheSphereOnly)
{
  AnatomyEditOptions o;
  o.radiusMm = 6.0;
  o.depthMm = 2.0;
  const std::array<double, 3> wall{ 15.0, 15.0, 15.0 };
  for (const AnatomyEditKind kind :
    { AnatomyEditKind::GrowTissue, AnatomyEditKind::ShrinkTissue, AnatomyEditKind::FillAir })
  {
    CTVolume v = airAgainstTissue();
    EXPECT_GT(applyAnatomyEdits(v, { { kind, wall } }, o), 0u) << anatomyEditKindName(kind);
    // 1.5 mm into the air and into the tissue, at the sphere's centre...
    const float air = valueAt(v, { 13.5, 15.0, 15.0 });
    const float tissue = valueAt(v, { 16.0, 15.0, 15.0 });
    // ...and 3 mm into the air, which only filling reaches.
    const float deepAir = valueAt(v, { 12.0, 15.0, 15.0 });
    switch (kind)
    {
      case AnatomyEditKind::GrowTissue:
        EXPECT_EQ(air, 40.0f);
        EXPECT_EQ(tissue, 40.0f);
        EXPECT_EQ(deepAir, -1000.0f);
        break;
      case AnatomyEditKind::ShrinkTissue:
        EXPECT_EQ(air, -1000.0f);
        EXPECT_EQ(tissue, -1000.0f);
        break;
      case AnatomyEditKind::FillAir:
        EXPECT_EQ(air, 40.0f);
        EXPECT_EQ(deepAir, 40.0f);
        break;
    }
    // Outside the sphere nothing changes.
    EXPECT_EQ(valueAt(v, { 13.5, 15.0, 22.0 }), -1000.0f);
    EXPECT_EQ(valueAt(v, { 16.0, 15.0, 22.0 }), 40.0f);
  }
}

TEST(AnatomyEdits, PlacesEditsApartOnTheWallInTurnAndRepeatably)
{
  std::vector<std::array<double, 3>> wall;
  for (int j = 0; j < 100; ++j)
  {
    for (int k = 0; k < 100; ++k)
    {
      wall.push_back({ 15.0, 0.5 * j, 0.5 * k });
    }
  }
  AnatomyEditOptions o;
  o.count = 3;
  o.seed = 4;
  const std::vector<AnatomyEdit> edits = placeAnatomyEdits(wall, o);
  ASSERT_EQ(edits.size(), 3u);
  EXPECT_EQ(edits[0].kind, AnatomyEditKind::GrowTissue);
  EXPECT_EQ(edits[1].kind, AnatomyEditKind::ShrinkTissue);
  EXPECT_EQ(edits[2].kind, AnatomyEditKind::FillAir);
  for (std::size_t a = 0; a < edits.size(); ++a)
  {
    for (std::size_t b = a + 1; b < edits.size(); ++b)
    {
      const double apart = std::hypot(edits[a].centreMm[0] - edits[b].centreMm[0],
        edits[a].centreMm[1] - edits[b].centreMm[1], edits[a].centreMm[2] - edits[b].centreMm[2]);
      EXPECT_GE(apart, 2.0 * (o.radiusMm + o.depthMm));
    }
  }
  EXPECT_EQ(placeAnatomyEdits(wall, o)[1].centreMm, edits[1].centreMm);
  EXPECT_TRUE(nearAnatomyEdit(edits[0].centreMm, edits, o));
  EXPECT_FALSE(nearAnatomyEdit({ 100.0, 100.0, 100.0 }, edits, o));
  // A wall too small for more edits gets fewer.
  o.count = 20;
  EXPECT_LT(placeAnatomyEdits(wall, o).size(), 20u);
}

TEST(AnatomyEdits, RefusesValuesOutOfRange)
{
  AnatomyEditOptions o;
  o.count = 21;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "anatomy edits: count (0-20) 21 is out of range");
  o = AnatomyEditOptions();
  o.radiusMm = 0.5;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "anatomy edits: radius (1-20 mm) 0.5 is out of range");
  o = AnatomyEditOptions();
  o.depthMm = 6.0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "anatomy edits: depth (0.5-5 mm) 6 is out of range");
}

namespace
{

/// The six walls of the box [lo, hi] as 1 mm grids, normals into the box
/// (each wall its own vertices, so every vertex has its wall's normal).
TriangleMesh gridBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
{
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  for (int axis = 0; axis < 3; ++axis)
  {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    const int nu = static_cast<int>(std::lround(hi[u] - lo[u]));
    const int nw = static_cast<int>(std::lround(hi[w] - lo[w]));
    for (const double at : { lo[axis], hi[axis] })
    {
      const int first = static_cast<int>(v.size());
      for (int b = 0; b <= nw; ++b)
      {
        for (int a = 0; a <= nu; ++a)
        {
          Eigen::Vector3d p;
          p[axis] = at;
          p[u] = lo[u] + a;
          p[w] = lo[w] + b;
          v.push_back(p);
        }
      }
      for (int b = 0; b < nw; ++b)
      {
        for (int a = 0; a < nu; ++a)
        {
          const int i = first + b * (nu + 1) + a;
          for (Eigen::Vector3i t :
            { Eigen::Vector3i(i, i + 1, i + nu + 2), Eigen::Vector3i(i, i + nu + 2, i + nu + 1) })
          {
            const Eigen::Vector3d n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
            if (n.dot(centre - v[t[0]]) < 0.0)
            {
              std::swap(t[1], t[2]);
            }
            f.push_back(t);
          }
        }
      }
    }
  }
  return TriangleMesh(std::move(v), std::move(f));
}

/// A nose in LPS mm: two passages x in [-9, -1] and [1, 9] (y 0-60, z 0-40)
/// either side of a 2 mm septum at x = 0, and in the CT a maxillary sinus of
/// air on each side (|x| 14-30, y 10-30, z -5 to 15); the rest is tissue.
/// The left "sinus" may reach the volume's front: air outside the head.
struct Nose
{
  TriangleMesh airway;
  CTVolume ct;
};

Nose makeNose(bool leftSinusOpenToTheFront = false)
{
  Nose nose;
  nose.airway = merge({ gridBox({ -9.0, 0.0, 0.0 }, { -1.0, 60.0, 40.0 }),
    gridBox({ 1.0, 0.0, 0.0 }, { 9.0, 60.0, 40.0 }) });
  CTVolume& ct = nose.ct;
  ct.dims = { 81, 61, 56 };
  ct.originMm = { -40.0, 0.0, -15.0 };
  ct.intensities.assign(ct.numberOfVoxels(), 40.0f);
  std::size_t n = 0;
  for (int k = 0; k < ct.dims[2]; ++k)
  {
    for (int j = 0; j < ct.dims[1]; ++j)
    {
      for (int i = 0; i < ct.dims[0]; ++i, ++n)
      {
        const std::array<double, 3> p = ct.indexToPhysical({ double(i), double(j), double(k) });
        const double side = std::abs(p[0]);
        const bool passage = side > 1.0 && side < 9.0 && p[2] > 0.0 && p[2] < 40.0;
        const bool open = leftSinusOpenToTheFront && p[0] > 0.0;
        const bool sinus = side >= 14.0 && side <= 30.0 && p[1] >= (open ? 0.0 : 10.0) &&
          p[1] <= 30.0 && p[2] >= -5.0 && p[2] <= 15.0;
        ct.intensities[n] = passage || sinus ? -1000.0f : 40.0f;
      }
    }
  }
  return nose;
}

} // namespace

TEST(AnatomyEdits, AnatomicalSitesAreTheSeptumTheTurbinatesAndTheSinusFloorOnOpposingSides)
{
  const Nose nose = makeNose();
  AnatomyEditOptions o;
  o.placement = AnatomyEditPlacement::AnatomicalSites;
  o.count = 4;
  o.radiusMm = 3.0;
  o.depthMm = 1.0;
  for (std::uint32_t seed : { 1u, 2u, 3u, 4u })
  {
    o.seed = seed;
    const std::vector<AnatomyEdit> edits = placeAnatomicalEdits(nose.airway, nose.ct, o);
    ASSERT_EQ(edits.size(), 4u) << "seed " << seed;
    EXPECT_EQ(edits[0].site, "septum");
    EXPECT_EQ(edits[1].site, "inferior turbinate");
    EXPECT_EQ(edits[2].site, "middle turbinate");
    EXPECT_EQ(edits[3].site, "maxillary sinus");
    EXPECT_EQ(edits[0].kind, AnatomyEditKind::GrowTissue);
    EXPECT_EQ(edits[1].kind, AnatomyEditKind::GrowTissue);
    EXPECT_EQ(edits[2].kind, AnatomyEditKind::ShrinkTissue);
    EXPECT_EQ(edits[3].kind, AnatomyEditKind::FillAir);
    // The deviation's side, then the nasal cavity's region: z 8-24 mm, y 0-36
    // mm (the turbinates behind y 7.2), middle height 16 mm.
    const double side = edits[0].centreMm[0] > 0.0 ? 1.0 : -1.0;
    EXPECT_DOUBLE_EQ(edits[0].centreMm[0], side * 1.0);
    EXPECT_DOUBLE_EQ(edits[1].centreMm[0], -side * 9.0);
    EXPECT_LT(edits[1].centreMm[2], 16.0);
    EXPECT_GT(edits[1].centreMm[1], 7.2);
    EXPECT_DOUBLE_EQ(edits[2].centreMm[0], side * 9.0);
    EXPECT_GE(edits[2].centreMm[2], 16.0);
    // The sinus beside the other passage, at its lowest point 4 mm from its floor.
    EXPECT_LE(-side * edits[3].centreMm[0], 26.0);
    EXPECT_GE(-side * edits[3].centreMm[0], 18.0);
    EXPECT_DOUBLE_EQ(edits[3].centreMm[2], -1.0);
    EXPECT_EQ(placeAnatomicalEdits(nose.airway, nose.ct, o)[1].centreMm, edits[1].centreMm);
  }
  // Fewer edits take the first sites.
  o.count = 2;
  const std::vector<AnatomyEdit> two = placeAnatomicalEdits(nose.airway, nose.ct, o);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[1].site, "inferior turbinate");
}

TEST(AnatomyEdits, AnatomicalSitesRefuseMoreThanFourEditsAndAnAirwayWithoutSagittalWalls)
{
  const Nose nose = makeNose();
  AnatomyEditOptions o;
  o.placement = AnatomyEditPlacement::AnatomicalSites;
  o.count = 5;
  EXPECT_EQ(fixtures::errorMessageOf([&] { o.validate(); }),
    "anatomy edits: the anatomical sites hold at most 4 edits, not 5");
  o.count = 4;
  // A box of two triangles a side: its corners' normals are diagonal.
  EXPECT_EQ(fixtures::errorMessageOf(
              [&] {
                placeAnatomicalEdits(makeBox({ -9.0, 0.0, 0.0 }, { 9.0, 60.0, 40.0 }), nose.ct, o);
              }),
    "anatomical edits: the airway has no near-sagittal walls in the nasal cavity (is it a nasal "
    "airway in the CT frame, LPS?)");
}

TEST(AnatomyEdits, AnatomicalSitesTakeNoAirOpenToTheOutsideForASinus)
{
  const Nose nose = makeNose(true);
  AnatomyEditOptions o;
  o.placement = AnatomyEditPlacement::AnatomicalSites;
  o.count = 4;
  o.radiusMm = 3.0;
  o.depthMm = 1.0;
  int leftSinusSkipped = 0;
  for (std::uint32_t seed : { 1u, 2u, 3u, 4u, 5u, 6u })
  {
    o.seed = seed;
    const std::vector<AnatomyEdit> edits = placeAnatomicalEdits(nose.airway, nose.ct, o);
    ASSERT_FALSE(edits.empty());
    // The sinus goes beside the passage opposite the deviation.
    const bool sinusOnTheLeft = edits[0].centreMm[0] < 0.0;
    EXPECT_EQ(edits.size(), sinusOnTheLeft ? 3u : 4u) << "seed " << seed;
    leftSinusSkipped += sinusOnTheLeft ? 1 : 0;
  }
  EXPECT_GT(leftSinusSkipped, 0);
}
