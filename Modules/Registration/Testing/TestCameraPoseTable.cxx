#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Registration/CameraPoseTable.h>

#include <gtest/gtest.h>

#include <vtkDoubleArray.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkTable.h>

using namespace vimlop;

namespace
{

std::vector<FramePose> makePoses()
{
  std::vector<FramePose> poses;
  for (int i = 0; i < 5; ++i)
  {
    FramePose p;
    p.frameId = 3 * i + 1;
    p.cameraToWorld.rotation = rotationFromVector(Eigen::Vector3d(0.1 * i, -0.2, 0.3 + 0.05 * i));
    p.cameraToWorld.centre = Eigen::Vector3d(10.0 + i, -20.0, 5.5 * i);
    poses.push_back(p);
  }
  return poses;
}

} // namespace

TEST(CameraPoseTable, RoundTrip)
{
  const std::vector<FramePose> poses = makePoses();
  const vtkSmartPointer<vtkTable> table = makeCameraPoseTable(poses);
  ASSERT_EQ(table->GetNumberOfRows(), 5);
  const std::vector<FramePose> back = readCameraPoseTable(table);
  ASSERT_EQ(back.size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i)
  {
    EXPECT_EQ(back[i].frameId, poses[i].frameId);
    EXPECT_LT((back[i].cameraToWorld.matrix() - poses[i].cameraToWorld.matrix()).norm(), 1e-12);
  }
}

TEST(CameraPoseTable, RowsLoadIntoVTKMatrices)
{
  // The documented layout: row-major, what vtkMatrix4x4::DeepCopy expects.
  const std::vector<FramePose> poses = makePoses();
  const vtkSmartPointer<vtkTable> table = makeCameraPoseTable(poses);
  auto* column = vtkDoubleArray::SafeDownCast(table->GetColumnByName("CameraToCT"));
  ASSERT_NE(column, nullptr);
  double elements[16];
  column->GetTypedTuple(2, elements);
  vtkNew<vtkMatrix4x4> m;
  m->DeepCopy(elements);
  const Eigen::Vector3d c = poses[2].cameraToWorld.centre;
  EXPECT_DOUBLE_EQ(m->GetElement(0, 3), c.x());
  EXPECT_DOUBLE_EQ(m->GetElement(2, 3), c.z());
  EXPECT_DOUBLE_EQ(m->GetElement(1, 2), poses[2].cameraToWorld.rotation(1, 2));
}

TEST(CameraPoseTable, RejectsMalformedTables)
{
  vtkNew<vtkTable> empty;
  try
  {
    readCameraPoseTable(empty);
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "camera pose table: missing numeric column 'FrameId'");
  }
  const vtkSmartPointer<vtkTable> table = makeCameraPoseTable(makePoses());
  auto* column = vtkDoubleArray::SafeDownCast(table->GetColumnByName("CameraToCT"));
  column->SetTypedComponent(3, 0, 5.0); // no longer a rotation
  try
  {
    readCameraPoseTable(table);
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(),
      "camera pose table, row 3: camera pose matrix: upper-left 3x3 block is not a rotation");
  }
  EXPECT_THROW(readCameraPoseTable(nullptr), Error);
}

TEST(CameraPoseTable, TrackedFramesAddTheirStateAndLatencyAfterThePoses)
{
  const std::vector<FramePose> poses = makePoses();
  const std::vector<std::string> states = { "tracking", "degraded", "lost", "tracking",
    "tracking" };
  const std::vector<double> latencyMs = { 5.0, 6.5, 7.0, 8.25, 9.0 };
  const vtkSmartPointer<vtkTable> table = makeTrackedPoseTable(poses, states, latencyMs);
  ASSERT_EQ(table->GetNumberOfColumns(), 4);
  EXPECT_EQ(readCameraPoseTable(table)[2].frameId, poses[2].frameId);
  EXPECT_EQ(table->GetValueByName(2, "State").ToString(), "lost");
  EXPECT_DOUBLE_EQ(table->GetValueByName(3, "LatencyMs").ToDouble(), 8.25);
  try
  {
    makeTrackedPoseTable(poses, { "tracking" }, latencyMs);
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(
      e.what(), "tracked pose table: 5 poses, 1 states and 5 latencies: one of each per frame");
  }
}
