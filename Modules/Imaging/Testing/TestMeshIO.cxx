#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkPolyData.h>

#include <fstream>

using namespace vimlop;

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;

} // namespace

class MeshRoundTrip : public ::testing::TestWithParam<std::string>
{
};

TEST_P(MeshRoundTrip, KeepsVerticesFacesAndOrientation)
{
  const TriangleMesh sphere = fixtures::makeSphere(7.5, 2, { 1, 2, 3 });
  const std::string path = out + "/sphere" + GetParam();
  writePolyData(toPolyData(sphere), path);
  const TriangleMesh back = toTriangleMesh(readPolyData(path));
  ASSERT_EQ(back.numberOfFaces(), sphere.numberOfFaces());
  EXPECT_NEAR(back.totalArea(), sphere.totalArea(), 1e-3);
  // STL stores vertices per face and in float; compare geometry, not indices.
  for (int f = 0; f < sphere.numberOfFaces(); ++f)
  {
    ASSERT_LT((back.faceCentroid(f) - sphere.faceCentroid(f)).norm(), 1e-4);
    ASSERT_GT(back.faceNormals()[f].dot(sphere.faceNormals()[f]), 0.9999);
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, MeshRoundTrip, ::testing::Values(".vtp", ".vtk", ".stl", ".ply"),
  [](const auto& info) { return info.param.substr(1); });

TEST(MeshIO, ConversionTriangulatesPolygons)
{
  auto quad = toPolyData(fixtures::makeBox({ 0, 0, 0 }, { 1, 1, 1 }));
  EXPECT_EQ(toTriangleMesh(quad).numberOfFaces(), 12);
  vtkNew<vtkPolyData> empty;
  EXPECT_THROW(toTriangleMesh(empty), Error);
}

TEST(MeshIO, ConversionDropsTrianglesThatRepeatAPoint)
{
  // Decimation and point merging in other tools leave triangles such as
  // (a, a, b); they cover no surface and must not make the mesh unusable.
  auto box = toPolyData(fixtures::makeBox({ 0, 0, 0 }, { 1, 1, 1 }));
  const vtkIdType degenerate[3][3] = { { 0, 0, 1 }, { 2, 3, 3 }, { 4, 5, 4 } };
  for (const auto& ids : degenerate)
  {
    box->GetPolys()->InsertNextCell(3, ids);
  }
  ASSERT_EQ(box->GetNumberOfPolys(), 15);
  EXPECT_EQ(toTriangleMesh(box).numberOfFaces(), 12);
}

TEST(MeshIO, ErrorsNameTheFileAndTheProblem)
{
  auto message = [](const std::string& path)
  {
    try
    {
      readPolyData(path);
    }
    catch (const Error& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(out + "/none.vtp"), "'" + out + "/none.vtp': no such file");
  std::ofstream(out + "/garbage.vtp") << "<not vtk>";
  EXPECT_EQ(
    message(out + "/garbage.vtp"), "'" + out + "/garbage.vtp': not a VTK XML polydata file");
  std::ofstream(out + "/garbage.ply") << "nothing";
  EXPECT_EQ(message(out + "/garbage.ply"), "'" + out + "/garbage.ply': not a PLY file");
  std::ofstream(out + "/mesh.off") << "OFF";
  EXPECT_EQ(message(out + "/mesh.off"),
    "'" + out + "/mesh.off': unsupported mesh file type (expected .vtp, .vtk, .stl, .ply or .obj)");
  EXPECT_THROW(
    writePolyData(toPolyData(fixtures::makeBox({ 0, 0, 0 }, { 1, 1, 1 })), out + "/x.obj"), Error);
}
