#include <vimlop/Core/FramePose.h>

#include <vimlop/Core/Error.h>

#include <sstream>
#include <unordered_map>

namespace vimlop
{

void checkFramePoses(const std::vector<FramePose>& poses)
{
  std::unordered_map<int, size_t> firstIndexOf;
  for (size_t i = 0; i < poses.size(); ++i)
  {
    const FramePose& pose = poses[i];
    const auto [earlier, inserted] = firstIndexOf.emplace(pose.frameId, i);
    std::ostringstream problem;
    if (!inserted)
    {
      problem << "frame id " << pose.frameId << " repeats pose " << earlier->second << "'s";
    }
    else if (!pose.cameraToWorld.centre.allFinite() || !pose.cameraToWorld.rotation.allFinite())
    {
      problem << "the camera of frame " << pose.frameId << " is not finite";
    }
    else if (pose.cameraToWorld.centre.norm() > maxFramePoseDistanceMm)
    {
      problem << "the camera of frame " << pose.frameId << " lies "
              << pose.cameraToWorld.centre.norm()
              << " mm from the origin, farther than 1 km: not a pose in a CT";
    }
    if (!problem.str().empty())
    {
      throw Error("pose " + std::to_string(i) + ": " + problem.str());
    }
  }
}

} // namespace vimlop
