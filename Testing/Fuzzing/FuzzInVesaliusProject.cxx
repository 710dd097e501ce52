// Fuzzes the .inv3 reader: tar framing, member sizes, the plist and the
// matrix checks. Raw (non-gzip) bytes reach the tar parser directly, because
// zlib reads uncompressed files transparently.
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/InVesaliusProjectReader.h>

#include <vtkObject.h>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  // VTK's XML parser reports every malformed plist on stderr; the reader turns
  // those into vimlop::Error anyway, and the messages would slow the fuzzer.
  vtkObject::GlobalWarningDisplayOff();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string path = vimlop::fuzzing::writeInput(data, size, ".inv3");
  try
  {
    vimlop::readInVesaliusProject(path);
  }
  catch (const vimlop::Error&)
  {
    // Rejecting bad input with a message is the expected outcome.
  }
  return 0;
}
