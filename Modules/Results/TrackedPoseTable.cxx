#include <vimlop/Results/TrackedPoseTable.h>

#include <vimlop/Registration/CameraPoseTable.h>

#include "TableFile.h"

#include <vtkTable.h>

namespace vimlop
{

void writeTrackedPoseTable(const std::vector<TrackedPoseRow>& rows, const std::string& path)
{
  std::vector<FramePose> poses;
  std::vector<std::string> states;
  std::vector<double> latencyMs;
  for (const TrackedPoseRow& row : rows)
  {
    poses.push_back(row.pose);
    states.push_back(row.state);
    latencyMs.push_back(row.latencyMs);
  }
  detail::writeTableFile(makeTrackedPoseTable(poses, states, latencyMs), path);
}

} // namespace vimlop
