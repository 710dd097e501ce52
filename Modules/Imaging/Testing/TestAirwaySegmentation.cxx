#include "AirwayPhantom.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/AirwaySegmentation.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace vimlop;
using fixtures::HeadPhantom;

namespace
{

std::string messageOf(const CTVolume& ct, const AirwaySegmentationOptions& options)
{
  try
  {
    AirwaySegmentation::compute(ct, options);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

float labelAt(const AirwaySegmentation& s, int i, int j, int k)
{
  const CTVolume& l = s.label;
  return l.intensities[static_cast<std::size_t>(i) +
    static_cast<std::size_t>(l.dims[0]) * (j + static_cast<std::size_t>(l.dims[1]) * k)];
}

bool allIn(const AirwaySegmentation& s, std::array<int, 6> box, float value)
{
  for (int k = box[4]; k <= box[5]; ++k)
  {
    for (int j = box[2]; j <= box[3]; ++j)
    {
      for (int i = box[0]; i <= box[1]; ++i)
      {
        if (labelAt(s, i, j, k) != value)
        {
          return false;
        }
      }
    }
  }
  return true;
}

} // namespace

TEST(AirwaySegmentation, ChoosesTheLargestAirSpaceInsideTheHead)
{
  const CTVolume ct = HeadPhantom::make();
  int calls = 0;
  double last = -1.0;
  bool monotone = true;
  const AirwaySegmentation s = AirwaySegmentation::compute(ct, AirwaySegmentationOptions(),
    [&](double fraction, const std::string&)
    {
      monotone = monotone && fraction >= last;
      last = fraction;
      ++calls;
    });
  EXPECT_GT(calls, 3);
  EXPECT_TRUE(monotone);
  EXPECT_EQ(last, 1.0);
  EXPECT_EQ(s.selection, "largest");
  // The airway box is all in; the sinus (behind a one-voxel wall), the air
  // cell, the outside air and the air between head and head rest are out.
  EXPECT_TRUE(allIn(s, HeadPhantom::kAirwayBox, 1.0f));
  EXPECT_TRUE(allIn(s, HeadPhantom::kSinusBox, 0.0f));
  EXPECT_TRUE(allIn(s, HeadPhantom::kCellBox, 0.0f));
  EXPECT_EQ(labelAt(s, 0, 0, 0), 0.0f);
  EXPECT_EQ(labelAt(s, 10, 4, 24), 0.0f); // between the head and the head rest
  // The nostril channel counts up to where it leaves the head (k of about 7).
  const int airway = HeadPhantom::boxVoxels(HeadPhantom::kAirwayBox);
  EXPECT_GE(s.voxelCount, static_cast<std::size_t>(airway + 16 * 5));
  EXPECT_LE(s.voxelCount, static_cast<std::size_t>(airway + 16 * 9));
  EXPECT_EQ(labelAt(s, 31, 45, 0), 0.0f);
  EXPECT_EQ(labelAt(s, 31, 45, 10), 1.0f);
  EXPECT_DOUBLE_EQ(s.volumeMm3, static_cast<double>(s.voxelCount));
  // Airway, sinus and cell: three interior air components.
  EXPECT_EQ(s.interiorAirComponents, 3);
  EXPECT_DOUBLE_EQ(s.nextLargestVolumeMm3, HeadPhantom::boxVoxels(HeadPhantom::kSinusBox));
  // Geometry: the airway's bounds and centroid (identity grid: index = mm).
  EXPECT_DOUBLE_EQ(s.boundsMm[0], 28.0);
  EXPECT_DOUBLE_EQ(s.boundsMm[1], 36.0);
  EXPECT_DOUBLE_EQ(s.boundsMm[3], 50.0);
  EXPECT_DOUBLE_EQ(s.boundsMm[5], 24.0);
  EXPECT_NEAR(s.centroidMm[0], 32.0, 0.3);
  // The head mask reaches from the head rest (j = 1) to the face (j = 59).
  EXPECT_DOUBLE_EQ(s.headBoundsMm[2], 1.0);
  EXPECT_DOUBLE_EQ(s.headBoundsMm[3], 59.0);
  // The label keeps the CT's grid.
  EXPECT_EQ(s.label.dims, ct.dims);
  EXPECT_EQ(s.label.direction, ct.direction);
}

TEST(AirwaySegmentation, ClosingTheHeadMaskCanEncloseAirAtTheHeadRest)
{
  // Why the closing is off by default: it joins the head and the pad under
  // it, and the air between them becomes "inside the head".
  AirwaySegmentationOptions closing;
  closing.bodyClosingRadiusMm = 2.0;
  const AirwaySegmentation s = AirwaySegmentation::compute(HeadPhantom::make(), closing);
  EXPECT_GT(s.interiorAirComponents, 3);
  // Here the airway is still the largest.
  EXPECT_TRUE(allIn(s, HeadPhantom::kAirwayBox, 1.0f));
  EXPECT_EQ(labelAt(s, 28, 5, 24), 0.0f);
}

TEST(AirwaySegmentation, SeedAndSinusOptionsChangeTheChoice)
{
  const CTVolume ct = HeadPhantom::make();
  AirwaySegmentationOptions options;
  options.minimumVolumeMm3 = 100.0;
  options.seedMm = std::array<double, 3>{ 40.0, 44.0, 18.0 }; // in the sinus
  const AirwaySegmentation sinus = AirwaySegmentation::compute(ct, options);
  EXPECT_EQ(sinus.selection, "seed");
  EXPECT_EQ(
    sinus.voxelCount, static_cast<std::size_t>(HeadPhantom::boxVoxels(HeadPhantom::kSinusBox)));
  EXPECT_TRUE(allIn(sinus, HeadPhantom::kAirwayBox, 0.0f));

  // The wall between airway and sinus is one voxel: their voxel centres are
  // 2 mm apart. 1.5 mm leaves the sinus out, 2.5 mm brings it in, and the
  // air cell (far away) stays out.
  AirwaySegmentationOptions near;
  near.sinusInclusionDistanceMm = 1.5;
  EXPECT_EQ(AirwaySegmentation::compute(ct, near).includedSinuses, 0);
  near.sinusInclusionDistanceMm = 2.5;
  const AirwaySegmentation both = AirwaySegmentation::compute(ct, near);
  EXPECT_EQ(both.includedSinuses, 1);
  EXPECT_DOUBLE_EQ(both.includedSinusVolumeMm3, HeadPhantom::boxVoxels(HeadPhantom::kSinusBox));
  EXPECT_TRUE(allIn(both, HeadPhantom::kSinusBox, 1.0f));
  EXPECT_TRUE(allIn(both, HeadPhantom::kCellBox, 0.0f));
  EXPECT_DOUBLE_EQ(both.nextLargestVolumeMm3, HeadPhantom::boxVoxels(HeadPhantom::kCellBox));
}

TEST(AirwaySegmentation, WorksInTheCTFrameWithAReflectedDirection)
{
  // The phantom stored with rows reversed and direction diag(1, -1, 1), as an
  // InVesalius project: the same head in the same physical place.
  const CTVolume plain = HeadPhantom::make();
  CTVolume flipped = plain;
  flipped.direction = { 1, 0, 0, 0, -1, 0, 0, 0, 1 };
  flipped.originMm = { 0.0, 63.0, 0.0 };
  for (int k = 0; k < 48; ++k)
  {
    for (int j = 0; j < 64; ++j)
    {
      for (int i = 0; i < 64; ++i)
      {
        flipped.intensities[i + 64 * ((63 - j) + 64 * k)] =
          plain.intensities[i + 64 * (j + 64 * k)];
      }
    }
  }
  const AirwaySegmentation a = AirwaySegmentation::compute(plain, AirwaySegmentationOptions());
  const AirwaySegmentation b = AirwaySegmentation::compute(flipped, AirwaySegmentationOptions());
  EXPECT_EQ(a.voxelCount, b.voxelCount);
  for (int axis = 0; axis < 3; ++axis)
  {
    EXPECT_NEAR(a.centroidMm[axis], b.centroidMm[axis], 1e-9);
    EXPECT_NEAR(a.boundsMm[2 * axis], b.boundsMm[2 * axis], 1e-9);
    EXPECT_NEAR(a.boundsMm[2 * axis + 1], b.boundsMm[2 * axis + 1], 1e-9);
  }
  // A seed is a physical point: the same one works in both.
  AirwaySegmentationOptions seeded;
  seeded.seedMm = std::array<double, 3>{ 32.0, 44.0, 20.0 };
  EXPECT_EQ(AirwaySegmentation::compute(flipped, seeded).voxelCount, a.voxelCount);
}

TEST(AirwaySegmentation, DeepestPointsAreInsideAndSeparated)
{
  const AirwaySegmentation s =
    AirwaySegmentation::compute(HeadPhantom::make(), AirwaySegmentationOptions());
  const std::vector<AirwaySegmentation::InteriorPoint> points = s.deepestPoints(5, 3.0);
  ASSERT_FALSE(points.empty());
  // The airway box is 9 x 13 x 11 voxels: its centre line is 4 voxels deep.
  EXPECT_NEAR(points[0].depthMm, 4.0, 1e-6);
  for (std::size_t a = 0; a < points.size(); ++a)
  {
    const auto& p = points[a].pointMm;
    EXPECT_EQ(
      labelAt(s, int(std::lround(p[0])), int(std::lround(p[1])), int(std::lround(p[2]))), 1.0f);
    EXPECT_LE(points[a].depthMm, points[0].depthMm);
    for (std::size_t b = 0; b < a; ++b)
    {
      const auto& q = points[b].pointMm;
      EXPECT_GE(std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]), 3.0);
    }
  }
  AirwaySegmentation empty;
  EXPECT_THROW(empty.deepestPoints(3, 1.0), Error);
}

TEST(AirwaySegmentation, BadInputGetsOneLineErrors)
{
  const CTVolume ct = HeadPhantom::make();
  const AirwaySegmentationOptions defaults;

  CTVolume flat = fixtures::emptyVolume({ 64, 64, 1 });
  EXPECT_EQ(messageOf(flat, defaults), "the CT is 64 x 64 x 1 voxels: a 3-D volume is needed");

  AirwaySegmentationOptions nothing;
  nothing.airThresholdHU = -2000.0;
  EXPECT_EQ(messageOf(ct, nothing),
    "the air threshold -2000 HU selects no voxel (intensities span -1000 HU .. 900 HU)");
  AirwaySegmentationOptions everything;
  everything.airThresholdHU = 2000.0;
  EXPECT_EQ(messageOf(ct, everything),
    "the air threshold 2000 HU selects every voxel (intensities span -1000 HU .. 900 HU)");

  // A solid head: tissue, no air inside.
  CTVolume solid = fixtures::emptyVolume({ 40, 40, 30 });
  fixtures::paint(solid, fixtures::kSoftTissueHU,
    [](int i, int j, int k) {
      return fixtures::inBox(i, j, k, { 5, 34, 5, 34, 5, 24 });
    });
  EXPECT_EQ(messageOf(solid, defaults),
    "no air inside the head: no voxel below -400 HU is enclosed by tissue above -500 HU");
  // No tissue at all.
  EXPECT_EQ(
    messageOf(fixtures::emptyVolume({ 8, 8, 8 }), AirwaySegmentationOptions()).substr(0, 32),
    "the air threshold -400 HU select");
  CTVolume fog = fixtures::emptyVolume({ 8, 8, 8 });
  fog.intensities[0] = 100.0f;
  AirwaySegmentationOptions dense;
  dense.bodyThresholdHU = 200.0;
  EXPECT_EQ(messageOf(fog, dense),
    "no tissue above 200 HU: there is no head (intensities span -1000 HU .. 100 HU)");

  // Only a tiny pocket of air in the head.
  CTVolume pocket = solid;
  fixtures::paint(pocket, fixtures::kAirHU,
    [](int i, int j, int k) {
      return fixtures::inBox(i, j, k, { 18, 20, 18, 20, 12, 14 });
    });
  EXPECT_EQ(messageOf(pocket, defaults),
    "no airway inside the head: the largest air pocket below -400 HU is 27 mm^3 (at least 1000 "
    "mm^3 needed)");

  AirwaySegmentationOptions outside;
  outside.seedMm = std::array<double, 3>{ 32.0, 44.0, -3.0 };
  EXPECT_EQ(
    messageOf(ct, outside), "the seed point (32.0, 44.0, -3.0) mm is outside the CT volume");
  AirwaySegmentationOptions tissue;
  tissue.seedMm = std::array<double, 3>{ 32.0, 30.0, 30.0 };
  EXPECT_EQ(messageOf(ct, tissue),
    "the seed point (32.0, 30.0, 30.0) mm is in tissue (40 HU), not in air inside the head");
  AirwaySegmentationOptions outdoors;
  outdoors.seedMm = std::array<double, 3>{ 1.0, 60.0, 2.0 };
  EXPECT_EQ(messageOf(ct, outdoors),
    "the seed point (1.0, 60.0, 2.0) mm is in air outside the head (-1000 HU), not in air inside "
    "the head");
}
