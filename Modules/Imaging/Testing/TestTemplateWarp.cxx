#include "TestMeshes.h"
#include <vimlop/Core/Rotation.h>
#include <vimlop/Imaging/DisplacementField.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Imaging/TemplateWarp.h>

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>

#include <Eigen/Geometry>

#include <functional>

using namespace vimlop;

namespace
{

std::array<double, 3> toArray(const Eigen::Vector3d& v)
{
  return { v[0], v[1], v[2] };
}

Eigen::Vector3d toVector(const std::array<double, 3>& a)
{
  return Eigen::Vector3d(a[0], a[1], a[2]);
}

/// A field sampling the map `f` on a 24 x 20 x 18 grid of 2 x 2.5 x 3 mm
/// with an oblique direction, covering about (-20..25, -25..25, -25..30) mm.
DisplacementField sampled(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& f)
{
  DisplacementField field;
  field.dims = { 24, 20, 18 };
  field.spacingMm = { 2.0, 2.5, 3.0 };
  const Eigen::Matrix3d d = rotationFromVector(Eigen::Vector3d(0.2, -0.1, 0.3));
  for (int i = 0; i < 9; ++i)
  {
    field.direction[i] = d(i / 3, i % 3);
  }
  const Eigen::Vector3d centre = d * Eigen::Vector3d(23.0, 23.75, 25.5);
  field.originMm = toArray(Eigen::Vector3d(2.0, 0.0, 2.0) - centre);
  field.displacements.resize(3 * field.numberOfPoints());
  std::size_t n = 0;
  for (int k = 0; k < 18; ++k)
  {
    for (int j = 0; j < 20; ++j)
    {
      for (int i = 0; i < 24; ++i, ++n)
      {
        const Eigen::Vector3d x =
          toVector(field.indexToPhysical({ double(i), double(j), double(k) }));
        const Eigen::Vector3d u = f(x) - x;
        for (int a = 0; a < 3; ++a)
        {
          field.displacements[3 * n + a] = u[a];
        }
      }
    }
  }
  return field;
}

CameraPose somePose(const Eigen::Vector3d& centre)
{
  return CameraPose::lookAt(
    centre, centre + Eigen::Vector3d(1.0, -2.0, 0.5), Eigen::Vector3d(0, 0, 1));
}

} // namespace

TEST(DisplacementField, InterpolatesAffineMapsExactlyAndClampsOutside)
{
  Eigen::Matrix3d m;
  m << 1.05, 0.02, -0.03, -0.01, 0.97, 0.04, 0.03, 0.01, 1.02;
  const Eigen::Vector3d t(1.5, -2.0, 0.7);
  const DisplacementField field = sampled([&](const Eigen::Vector3d& x) { return m * x + t; });
  ASSERT_TRUE(field.isValid());
  for (const Eigen::Vector3d& x : { Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3.3, -7.1, 11.9),
         Eigen::Vector3d(-12.2, 8.8, -4.4) })
  {
    ASSERT_TRUE(field.contains(toArray(x)));
    EXPECT_LT((toVector(field.transformPoint(toArray(x))) - (m * x + t)).norm(), 1e-9);
    EXPECT_LT((mapJacobian(field, x) - m).norm(), 1e-9);
  }
  // Index and physical point round-trip.
  const std::array<double, 3> index =
    field.physicalToIndex(field.indexToPhysical({ 3.5, 7.25, 1.0 }));
  EXPECT_NEAR(index[1], 7.25, 1e-12);
  // Outside the grid the border continues: a point beyond the last x plane
  // moves like its projection onto it.
  const std::array<double, 3> inside = field.indexToPhysical({ 23.0, 5.0, 5.0 });
  const std::array<double, 3> outside = field.indexToPhysical({ 30.0, 5.0, 5.0 });
  EXPECT_FALSE(field.contains(outside));
  const std::array<double, 3> u = field.displacementAt(inside);
  const std::array<double, 3> v = field.displacementAt(outside);
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(u[a], v[a], 1e-12);
  }
  DisplacementField broken = field;
  broken.displacements.pop_back();
  EXPECT_FALSE(broken.isValid());
}

TEST(TemplateWarp, TranslationFieldMovesPosesExactly)
{
  const Eigen::Vector3d shift(3.25, -1.5, 0.75);
  const DisplacementField field = sampled([&](const Eigen::Vector3d& x) { return x + shift; });
  const CameraPose pose = somePose(Eigen::Vector3d(4.0, -3.0, 6.0));
  const CameraPose warped = warpCameraPose(pose, field);
  EXPECT_LT((warped.centre - (pose.centre + shift)).norm(), 1e-12);
  EXPECT_LT((warped.rotation - pose.rotation).norm(), 1e-12);
}

TEST(TemplateWarp, RotationFieldRotatesPosesExactly)
{
  // A rigid rotation by 20 degrees about an axis through c0, then a shift.
  const Eigen::Matrix3d q = rotationFromVector(Eigen::Vector3d(0.1, -0.25, 0.2));
  const Eigen::Vector3d c0(2.0, 1.0, -3.0);
  const Eigen::Vector3d t(0.5, 0.0, -1.0);
  const auto rigid = [&](const Eigen::Vector3d& x)
  { return Eigen::Vector3d(q * (x - c0) + c0 + t); };
  const DisplacementField field = sampled(rigid);
  std::vector<FramePose> poses;
  // One pose in the middle, one a fraction of a grid step from the border,
  // where the Jacobian is taken one-sided.
  poses.push_back({ 7, somePose(Eigen::Vector3d(1.0, 2.0, 3.0)) });
  const Eigen::Vector3d nearBorder = toVector(field.indexToPhysical({ 0.3, 10.0, 9.0 }));
  poses.push_back({ 3, somePose(nearBorder) });
  const std::vector<FramePose> warped = warpFramePoses(poses, field);
  ASSERT_EQ(warped.size(), 2u);
  EXPECT_EQ(warped[0].frameId, 7);
  EXPECT_EQ(warped[1].frameId, 3);
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    const CameraPose& before = poses[i].cameraToWorld;
    const CameraPose& after = warped[i].cameraToWorld;
    EXPECT_LT((after.centre - rigid(before.centre)).norm(), 1e-9) << i;
    EXPECT_LT((after.rotation - q * before.rotation).norm(), 1e-9) << i;
    EXPECT_TRUE(isRotation(after.rotation, 1e-9));
  }
}

TEST(TemplateWarp, ShearKeepsTheRotationPartOnly)
{
  // A pure shear's Jacobian is no rotation; the pose turns by its polar factor.
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
  shear(0, 1) = 0.2;
  const DisplacementField field = sampled([&](const Eigen::Vector3d& x) { return shear * x; });
  const CameraPose pose = somePose(Eigen::Vector3d::Zero());
  const CameraPose warped = warpCameraPose(pose, field);
  EXPECT_TRUE(isRotation(warped.rotation, 1e-9));
  EXPECT_LT((warped.rotation - nearestRotation(shear) * pose.rotation).norm(), 1e-9);
}

TEST(TemplateWarp, MeshesFollowTheMapWithNormalsStillIntoTheAir)
{
  const Eigen::Vector3d centre(1.0, -2.0, 3.0);
  const TriangleMesh sphere = fixtures::makeSphere(8.0, 3, centre);
  const Eigen::Matrix3d q = rotationFromVector(Eigen::Vector3d(0.0, 0.3, -0.4));
  const Eigen::Vector3d t(2.0, 1.0, -0.5);
  const auto map = [&](const Eigen::Vector3d& x) { return Eigen::Vector3d(1.1 * (q * x) + t); };
  const DisplacementField field = sampled(map);
  const vtkSmartPointer<vtkPolyData> warped = warpSurface(toPolyData(sphere), field);
  const TriangleMesh after = toTriangleMesh(warped);
  ASSERT_EQ(after.numberOfVertices(), sphere.numberOfVertices());
  const Eigen::Vector3d movedCentre = map(centre);
  for (int v = 0; v < after.numberOfVertices(); ++v)
  {
    EXPECT_LT((after.vertices()[v] - map(sphere.vertices()[v])).norm(), 1e-9);
  }
  vtkDataArray* normals = warped->GetCellData()->GetNormals();
  ASSERT_NE(normals, nullptr);
  for (int f = 0; f < after.numberOfFaces(); ++f)
  {
    const Eigen::Vector3d n(normals->GetTuple3(f));
    EXPECT_GT(n.dot((movedCentre - after.faceCentroid(f)).normalized()), 0.9);
    EXPECT_GT(n.dot(after.faceNormals()[f]), 0.999);
  }
}
