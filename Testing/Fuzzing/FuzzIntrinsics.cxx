// Fuzzes the intrinsics reader (both layouts, every FileStorage format).
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Video/IntrinsicsIO.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  // The first byte picks the format, the rest is the file.
  if (size < 1)
  {
    return 0;
  }
  static const char* const suffixes[] = { ".yaml", ".json", ".xml" };
  const std::string path = vimlop::fuzzing::writeInput(data + 1, size - 1, suffixes[data[0] % 3]);
  try
  {
    vimlop::readIntrinsics(path);
  }
  catch (const vimlop::Error&)
  {
  }
  return 0;
}
