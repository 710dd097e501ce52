// Fuzzes the CT reader in every format it accepts: VIMLOP's header checks
// (NRRD lines, MetaImage data size, finite spacing, orthonormal directions),
// the DICOM series geometry checks, and ITK's readers behind them. The first
// byte picks the layout; the rest holds the file, or the files of a folder
// separated by "=====" lines (see splitParts):
//   0 .nrrd  1 .mha  2 .nii  3 .nii.gz  4 one .dcm file
//   5 .mhd header + volume.raw  6 .nhdr header + volume.raw
//   7 a folder of up to three DICOM slices (the series checks)
// Seeds: small volumes cut from the bundled CT in each layout, and the CT
// files of the bad-input corpus.
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/CTVolumeIO.h>

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
  using namespace vimlop::fuzzing;
  const int layout = data[0] % 8;
  std::string path;
  if (layout <= 4)
  {
    static const char* const suffixes[] = { ".nrrd", ".mha", ".nii", ".nii.gz", ".dcm" };
    path = writeInput(data + 1, size - 1, suffixes[layout]);
  }
  else if (layout <= 6)
  {
    const std::string folder = emptyFolder("ct");
    const std::vector<std::string_view> parts = splitParts(data + 1, size - 1, 2);
    path = folder + (layout == 5 ? "/volume.mhd" : "/volume.nhdr");
    writeFile(path, parts[0]);
    writeFile(folder + "/volume.raw", parts[1]);
  }
  else
  {
    path = emptyFolder("ct");
    const std::vector<std::string_view> parts = splitParts(data + 1, size - 1, 3);
    for (std::size_t i = 0; i < parts.size(); ++i)
    {
      if (!parts[i].empty())
      {
        writeFile(path + "/slice" + std::to_string(i) + ".dcm", parts[i]);
      }
    }
  }
  try
  {
    vimlop::readCTVolume(path);
  }
  catch (const vimlop::Error&)
  {
    // Rejecting bad input with a message is the expected outcome.
  }
  return 0;
}
