// The nasal airway of the real head CT that Debian's invesalius-examples
// ships (installed by CMake/install-dependencies.sh).
#include <vimlop/Core/ClosestPointOnTriangle.h>
#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Imaging/AirwaySegmentation.h>
#include <vimlop/Imaging/AirwaySurface.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>

#include <gtest/gtest.h>

#include <vtkPolyData.h>
#include <vtkPolyDataConnectivityFilter.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

using namespace vimlop;

namespace
{

const std::string cranium = "/usr/share/doc/invesalius-examples/examples/Cranium.inv3";

/// Generalised winding number of a closed mesh about `p`: the sum of the
/// triangles' signed solid angles over 4 pi. +1 inside a surface whose normals
/// point out of it, -1 inside one whose normals point in, 0 outside.
double windingNumber(const TriangleMesh& mesh, const Eigen::Vector3d& p)
{
  double sum = 0.0;
  for (int f = 0; f < mesh.numberOfFaces(); ++f)
  {
    const Eigen::Vector3d a = mesh.corner(f, 0) - p;
    const Eigen::Vector3d b = mesh.corner(f, 1) - p;
    const Eigen::Vector3d c = mesh.corner(f, 2) - p;
    const double la = a.norm();
    const double lb = b.norm();
    const double lc = c.norm();
    sum += 2.0 *
      std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
  }
  return sum / (4.0 * M_PI);
}

/// Shared by the tests below: segmenting once keeps the suite fast.
class CraniumAirway : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    const CTVolume ct = readCTVolume(cranium);
    Segmentation = new AirwaySegmentation(AirwaySegmentation::compute(ct, {}));
    Surface = new AirwaySurface(AirwaySurface::compute(Segmentation->label, {}));
  }
  static void TearDownTestSuite()
  {
    delete Segmentation;
    delete Surface;
  }
  static AirwaySegmentation* Segmentation;
  static AirwaySurface* Surface;
};

AirwaySegmentation* CraniumAirway::Segmentation = nullptr;
AirwaySurface* CraniumAirway::Surface = nullptr;

} // namespace

TEST_F(CraniumAirway, IsAPlausibleNasalAirwayInTheLowerFrontOfTheHead)
{
  const AirwaySegmentation& s = *Segmentation;
  // The nasal cavity with the nasopharynx and the sinuses whose ostia are
  // open at this resolution (frontal, sphenoid, ethmoid cells, one maxillary
  // sinus): about 50 cm^3. A nasal cavity alone is 15-40 cm^3; the sinuses
  // add 10-40 cm^3.
  EXPECT_GT(s.volumeMm3, 30e3);
  EXPECT_LT(s.volumeMm3, 70e3);
  // Far larger than any other air space inside the head (the next is a
  // sealed-off sinus or mastoid cells), so the automatic choice is clear-cut.
  EXPECT_LT(s.nextLargestVolumeMm3, 0.2 * s.volumeMm3);
  // In LPS: anterior is -y, superior +z. The airway's centroid lies in the
  // front half and the lower half of the head, near the midline.
  const std::array<double, 6>& head = s.headBoundsMm;
  const double headCentreX = 0.5 * (head[0] + head[1]);
  const double headCentreZ = 0.5 * (head[4] + head[5]);
  // (The head mask's back includes the head rest, which the head lies on.)
  EXPECT_LT(s.centroidMm[1] - head[2], 0.4 * (head[3] - head[2]));
  EXPECT_LT(s.centroidMm[2], headCentreZ);
  EXPECT_NEAR(s.centroidMm[0], headCentreX, 15.0);
  // Its front reaches the nostrils, a few mm behind the most anterior tissue.
  EXPECT_LT(s.boundsMm[2] - head[2], 15.0);
}

TEST_F(CraniumAirway, SurfaceIsOneClosedPieceWithTheSegmentedVolume)
{
  const AirwaySurface& surface = *Surface;
  EXPECT_NEAR(surface.triangles, 30000, 300);
  EXPECT_EQ(surface.boundaryEdges, 0);
  // Decimation may pinch a few edges where two sheets of the cavity touch.
  EXPECT_LT(surface.nonManifoldEdges, 30);
  vtkNew<vtkPolyDataConnectivityFilter> pieces;
  pieces->SetInputData(surface.surface);
  pieces->SetExtractionModeToAllRegions();
  pieces->Update();
  EXPECT_EQ(pieces->GetNumberOfExtractedRegions(), 1);
  EXPECT_NEAR(surface.enclosedVolumeMm3, Segmentation->volumeMm3, 0.05 * Segmentation->volumeMm3);
}

TEST_F(CraniumAirway, DeepestPointsAreInsideWithTheNormalsFacingThem)
{
  const TriangleMesh mesh = toTriangleMesh(Surface->surface);
  const std::vector<AirwaySegmentation::InteriorPoint> points =
    Segmentation->deepestPoints(25, 8.0);
  ASSERT_EQ(points.size(), 25u);
  EXPECT_GT(points.front().depthMm, 5.0); // the sinuses have room
  for (const AirwaySegmentation::InteriorPoint& point : points)
  {
    const Eigen::Vector3d p(point.pointMm[0], point.pointMm[1], point.pointMm[2]);
    // Inside a surface whose normals point in (into the air): winding -1.
    EXPECT_NEAR(windingNumber(mesh, p), -1.0, 1e-6) << p.transpose();
    // The nearest surface point's face normal faces the point.
    double best = std::numeric_limits<double>::max();
    int bestFace = -1;
    Eigen::Vector3d nearest = p;
    for (int f = 0; f < mesh.numberOfFaces(); ++f)
    {
      const Eigen::Vector3d q =
        closestPointOnTriangle(p, mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2));
      const double d = (q - p).squaredNorm();
      if (d < best)
      {
        best = d;
        bestFace = f;
        nearest = q;
      }
    }
    ASSERT_GE(bestFace, 0);
    EXPECT_GT(mesh.faceNormals()[bestFace].dot((p - nearest).normalized()), 0.0) << p.transpose();
    // The depth is measured to the centres of the airway's border voxels; the
    // surface runs between those and the tissue voxels next to them, up to a
    // voxel (1.5 mm along z) further.
    EXPECT_GT(std::sqrt(best), point.depthMm - 0.3) << p.transpose();
    EXPECT_LT(std::sqrt(best), point.depthMm + 1.8) << p.transpose();
  }
}
