#include <vimlop/Registration/CameraPoseTable.h>

#include <vimlop/Core/Error.h>

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <string>

namespace vimlop
{

vtkSmartPointer<vtkTable> makeCameraPoseTable(const std::vector<FramePose>& poses)
{
  const auto n = static_cast<vtkIdType>(poses.size());
  vtkNew<vtkIntArray> ids;
  ids->SetName("FrameId");
  ids->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> matrices;
  matrices->SetName("CameraToCT");
  matrices->SetNumberOfComponents(16);
  matrices->SetNumberOfTuples(n);
  for (vtkIdType row = 0; row < n; ++row)
  {
    const FramePose& pose = poses[static_cast<size_t>(row)];
    ids->SetValue(row, pose.frameId);
    const Eigen::Matrix4d m = pose.cameraToWorld.matrix();
    for (int i = 0; i < 4; ++i)
    {
      for (int j = 0; j < 4; ++j)
      {
        matrices->SetTypedComponent(row, 4 * i + j, m(i, j));
      }
    }
  }
  auto table = vtkSmartPointer<vtkTable>::New();
  table->AddColumn(ids);
  table->AddColumn(matrices);
  return table;
}

vtkSmartPointer<vtkTable> makeTrackedPoseTable(const std::vector<FramePose>& poses,
  const std::vector<std::string>& states, const std::vector<double>& latencyMs)
{
  if (states.size() != poses.size() || latencyMs.size() != poses.size())
  {
    throw Error("tracked pose table: " + std::to_string(poses.size()) + " poses, " +
      std::to_string(states.size()) + " states and " + std::to_string(latencyMs.size()) +
      " latencies: one of each per frame");
  }
  const vtkSmartPointer<vtkTable> table = makeCameraPoseTable(poses);
  vtkNew<vtkStringArray> state;
  state->SetName("State");
  vtkNew<vtkDoubleArray> latency;
  latency->SetName("LatencyMs");
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    state->InsertNextValue(states[i]);
    latency->InsertNextValue(latencyMs[i]);
  }
  table->AddColumn(state);
  table->AddColumn(latency);
  return table;
}

std::vector<FramePose> readCameraPoseTable(vtkTable* table)
{
  if (!table)
  {
    throw Error("camera pose table: no table");
  }
  auto* ids = vtkArrayDownCast<vtkDataArray>(table->GetColumnByName("FrameId"));
  auto* matrices = vtkArrayDownCast<vtkDataArray>(table->GetColumnByName("CameraToCT"));
  if (!ids || ids->GetNumberOfComponents() != 1)
  {
    throw Error("camera pose table: missing numeric column 'FrameId'");
  }
  if (!matrices || matrices->GetNumberOfComponents() != 16)
  {
    throw Error("camera pose table: missing 16-component numeric column 'CameraToCT'");
  }
  std::vector<FramePose> poses;
  poses.reserve(static_cast<size_t>(table->GetNumberOfRows()));
  for (vtkIdType row = 0; row < table->GetNumberOfRows(); ++row)
  {
    Eigen::Matrix4d m;
    for (int i = 0; i < 4; ++i)
    {
      for (int j = 0; j < 4; ++j)
      {
        m(i, j) = matrices->GetComponent(row, 4 * i + j);
      }
    }
    FramePose pose;
    pose.frameId = static_cast<int>(ids->GetComponent(row, 0));
    try
    {
      pose.cameraToWorld = CameraPose::fromMatrix(m);
    }
    catch (const Error& e)
    {
      throw Error("camera pose table, row " + std::to_string(row) + ": " + e.what());
    }
    poses.push_back(pose);
  }
  return poses;
}

} // namespace vimlop
