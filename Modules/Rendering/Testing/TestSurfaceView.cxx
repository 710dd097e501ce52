#include "ErrorMessage.h"
#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Rendering/SurfaceView.h>

#include <gtest/gtest.h>

#include <vtkImageData.h>

#include <algorithm>
#include <cstdlib>

using namespace vimlop;

namespace
{

/// The largest difference of one channel between two pictures of the same size.
int largestDifference(vtkImageData* a, vtkImageData* b)
{
  const auto n = a->GetNumberOfPoints() * a->GetNumberOfScalarComponents();
  const auto* pa = static_cast<const unsigned char*>(a->GetScalarPointer());
  const auto* pb = static_cast<const unsigned char*>(b->GetScalarPointer());
  int largest = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    largest = std::max(largest, std::abs(static_cast<int>(pa[i]) - static_cast<int>(pb[i])));
  }
  return largest;
}

/// How many pixels are not black.
int litPixels(vtkImageData* picture)
{
  const auto* p = static_cast<const unsigned char*>(picture->GetScalarPointer());
  int lit = 0;
  for (vtkIdType i = 0; i < picture->GetNumberOfPoints(); ++i)
  {
    lit += (p[3 * i] | p[3 * i + 1] | p[3 * i + 2]) != 0;
  }
  return lit;
}

TEST(SurfaceView, AViewKeptForManyPosesDrawsEachAsAViewOfItsOwnWould)
{
  // A blob 40 mm ahead, seen from two places and with two image sizes.
  const TriangleMesh blob = fixtures::makeSphere(8.0, 3, { 0.0, 0.0, 40.0 }, /*outward=*/true);
  const PinholeCamera big = PinholeCamera::simulatedEndoscope();
  PinholeCamera small = big;
  small.widthPx /= 2;
  small.heightPx /= 2;
  small.fx /= 2.0;
  small.fy /= 2.0;
  small.cx /= 2.0;
  small.cy /= 2.0;
  const CameraPose ahead;
  // The same orientation 6 mm to the side: the blob moves across the picture.
  CameraPose aside;
  aside.centre = Eigen::Vector3d(6.0, 0.0, 0.0);

  SurfaceView view(blob);
  const auto first = view.render(big, ahead);
  const auto second = view.render(small, aside);
  const auto third = view.render(big, aside);
  const auto firstAlone = renderSurfaceView(blob, big, ahead);
  const auto secondAlone = renderSurfaceView(blob, small, aside);
  const auto thirdAlone = renderSurfaceView(blob, big, aside);
  int dims[3];
  second->GetDimensions(dims);
  EXPECT_EQ(dims[0], small.widthPx);
  EXPECT_EQ(dims[1], small.heightPx);
  EXPECT_LE(largestDifference(first, firstAlone), 1);
  EXPECT_LE(largestDifference(second, secondAlone), 1);
  EXPECT_LE(largestDifference(third, thirdAlone), 1);
  // The blob is seen, and from aside it is drawn elsewhere: the camera moved with the pose.
  EXPECT_GT(litPixels(first), 1000);
  EXPECT_GT(largestDifference(first, third), 50);
}

TEST(SurfaceView, RefusesAMeshWithoutFacesAndInvalidIntrinsics)
{
  EXPECT_EQ(fixtures::errorMessageOf([] { SurfaceView view{ TriangleMesh() }; }),
    "surface view: the mesh has no faces");
  SurfaceView view(fixtures::makeSphere(8.0, 1, { 0.0, 0.0, 40.0 }, true));
  PinholeCamera broken = PinholeCamera::simulatedEndoscope();
  broken.fx = -1.0;
  EXPECT_THROW(view.render(broken, CameraPose()), Error);
}

} // namespace
