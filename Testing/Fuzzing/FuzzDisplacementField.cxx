// Fuzzes the displacement-field reader (`vimlop warp --field`, P4's truth):
// ITK's readers and VIMLOP's checks of the grid and the vectors. The first
// byte picks the format, the rest is the file. Seeds: small fields written
// by writeDisplacementField in each format.
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/DisplacementFieldIO.h>

#include <itkObject.h>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  itk::Object::GlobalWarningDisplayOff(); // the reader reports errors itself
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 1)
  {
    return 0;
  }
  static const char* const suffixes[] = { ".nii", ".nii.gz", ".nrrd", ".mha" };
  const std::string path = vimlop::fuzzing::writeInput(data + 1, size - 1, suffixes[data[0] % 4]);
  try
  {
    vimlop::readDisplacementField(path);
  }
  catch (const vimlop::Error&)
  {
    // Rejecting bad input with a message is the expected outcome.
  }
  return 0;
}
