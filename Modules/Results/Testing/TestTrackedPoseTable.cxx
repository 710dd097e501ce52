#include <vimlop/Results/TrackedPoseTable.h>

#include <vimlop/Registration/CameraPoseTable.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkXMLTableReader.h>

using namespace vimlop;

TEST(TrackedPoseTable, HoldsEveryFramesPoseStateAndLatencyForAVtkPipeline)
{
  const std::string path =
    (fixtures::freshTestFolder("tracked-pose-table") / "tracked-poses.vtt").string();
  std::vector<TrackedPoseRow> rows(3);
  for (int i = 0; i < 3; ++i)
  {
    rows[static_cast<std::size_t>(i)].pose.frameId = 20 + i;
    rows[static_cast<std::size_t>(i)].pose.cameraToWorld.centre =
      Eigen::Vector3d(100.0 + i, 80.0, 40.0);
    rows[static_cast<std::size_t>(i)].latencyMs = 5.0 + i;
  }
  rows[0].state = "tracking";
  rows[1].state = "lost";
  rows[2].state = "degraded";
  writeTrackedPoseTable(rows, path);

  vtkNew<vtkXMLTableReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkTable* table = reader->GetOutput();
  ASSERT_EQ(table->GetNumberOfRows(), 3);
  // The poses read back as camera-poses.vtt's are.
  const std::vector<FramePose> poses = readCameraPoseTable(table);
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(poses[1].frameId, 21);
  EXPECT_LT((poses[2].cameraToWorld.centre - Eigen::Vector3d(102.0, 80.0, 40.0)).norm(), 1e-12);
  auto* state = vtkStringArray::SafeDownCast(table->GetColumnByName("State"));
  auto* latency = vtkDoubleArray::SafeDownCast(table->GetColumnByName("LatencyMs"));
  ASSERT_NE(state, nullptr);
  ASSERT_NE(latency, nullptr);
  EXPECT_EQ(state->GetValue(1), "lost");
  EXPECT_EQ(state->GetValue(2), "degraded");
  EXPECT_EQ(latency->GetValue(2), 7.0);

  EXPECT_EQ(fixtures::errorMessageOf([&] { writeTrackedPoseTable(rows, "/no/such/dir/t.vtt"); }),
    "'/no/such/dir/t.vtt': cannot write the table: its folder does not exist");
}
