// The summaries of a segmentation and its surface, as `vimlop segment` prints them.
#include <vimlop/Imaging/AirwaySegmentation.h>
#include <vimlop/Imaging/AirwaySurface.h>

#include <gtest/gtest.h>

using namespace vimlop;

TEST(AirwaySummaries, TheSegmentationSaysHowItChoseTheAirway)
{
  AirwaySegmentation airway;
  airway.volumeMm3 = 51234.0;
  airway.selection = "largest";
  airway.interiorAirComponents = 12;
  airway.nextLargestVolumeMm3 = 2500.0;
  airway.includedSinuses = 2;
  airway.centroidMm = { 1.25, -2.0, 30.0 };
  EXPECT_EQ(airway.summaryText(),
    "airway 51.2 cm^3 (largest of 12 interior air components; next largest 2.5 cm^3; 2 sinuses "
    "added), centroid (1.2, -2.0, 30.0) mm LPS");
  airway.selection = "seed";
  EXPECT_EQ(airway.summaryText().substr(0, 33), "airway 51.2 cm^3 (seeded, one of ");
}

TEST(AirwaySummaries, TheSurfaceWarnsOfOpenEdgesAndDroppedPieces)
{
  AirwaySurface surface;
  surface.triangles = 30000;
  surface.vertices = 15002;
  surface.enclosedVolumeMm3 = 50000.0;
  surface.areaMm2 = 12340.0;
  EXPECT_EQ(surface.summaryText(),
    "surface 30000 triangles, 15002 vertices, encloses 50.0 cm^3, area 123.4 cm^2, 0 open edges, "
    "0 non-manifold edges");
  EXPECT_TRUE(surface.warnings().empty());
  surface.droppedPieces = 3;
  surface.droppedTriangleFraction = 0.01;
  EXPECT_TRUE(surface.warnings().empty());
  surface.droppedTriangleFraction = 0.025;
  surface.boundaryEdges = 4;
  const std::vector<std::string> warnings = surface.warnings();
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0], "the surface has 4 open boundary edges and 0 non-manifold edges");
  EXPECT_EQ(warnings[1], "3 disconnected pieces (2.5% of the surface) were dropped");
}
