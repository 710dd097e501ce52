// Fuzzes the reader of VIMLOP's SfM files (vimlop sfm's output).
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Video/SfmReconstructionIO.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string path = vimlop::fuzzing::writeInput(data, size, ".json");
  try
  {
    const vimlop::SfmReconstruction reconstruction = vimlop::readSfmReconstruction(path);
    // What the reader accepted passes the checks the registration relies on.
    reconstruction.validate();
  }
  catch (const vimlop::Error&)
  {
  }
  return 0;
}
