// Fuzzes the tracker CSV reader and the interpolation of what it accepts.
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Video/TrackerTrajectory.h>

#include <cmath>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string path = vimlop::fuzzing::writeInput(data, size, ".csv");
  try
  {
    std::vector<std::string> warnings;
    const vimlop::TrackerTrajectory trajectory =
      vimlop::TrackerTrajectory::readCsv(path, &warnings);
    // What was accepted must be usable: positions inside the recording are finite.
    const double middle = 0.5 * (trajectory.startS() + trajectory.endS());
    for (const double smoothing : { 0.0, 0.05 })
    {
      const auto position = trajectory.positionAt(middle, smoothing);
      if (std::isfinite(middle) && position && !position->allFinite())
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
