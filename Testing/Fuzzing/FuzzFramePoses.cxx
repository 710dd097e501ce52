// Fuzzes the JSON pose file reader (template poses, warped poses).
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/FramePoseIO.h>

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string path = vimlop::fuzzing::writeInput(data, size, ".json");
  try
  {
    for (const vimlop::FramePose& pose : vimlop::readFramePoses(path))
    {
      // An accepted pose is a finite rigid transform.
      if (!pose.cameraToWorld.matrix().allFinite())
      {
        std::abort();
      }
    }
  }
  catch (const vimlop::Error&)
  {
  }
  return 0;
}
