// Fuzzes the reader of perturbation-study runs (the input of report plots).
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Results/PerturbationRuns.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string path = vimlop::fuzzing::writeInput(data, size, ".json");
  try
  {
    vimlop::readPerturbationRuns(path);
  }
  catch (const vimlop::Error&)
  {
  }
  return 0;
}
