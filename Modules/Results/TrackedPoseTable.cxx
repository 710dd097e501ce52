#include <vimlop/Results/TrackedPoseTable.h>

#include <vimlop/Registration/CameraPoseTable.h>

#include "TableFile.h"

#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

namespace vimlop
{

void writeTrackedPoseTable(const std::vector<TrackedPoseRow>& rows, const std::string& path)
{
  std::vector<FramePose> poses;
  for (const TrackedPoseRow& row : rows)
  {
    poses.push_back(row.pose);
  }
  const vtkSmartPointer<vtkTable> table = makeCameraPoseTable(poses);
  vtkNew<vtkStringArray> state;
  state->SetName("State");
  vtkNew<vtkDoubleArray> latency;
  latency->SetName("LatencyMs");
  for (const TrackedPoseRow& row : rows)
  {
    state->InsertNextValue(row.state);
    latency->InsertNextValue(row.latencyMs);
  }
  table->AddColumn(state);
  table->AddColumn(latency);
  detail::writeTableFile(table, path);
}

} // namespace vimlop
