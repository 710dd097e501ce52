// Local edits of the anatomy for P4's harder pairs, on a slab of air against
// tissue made in memory.
#include "ErrorMessage.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/AnatomyEdits.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace vimlop;

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
