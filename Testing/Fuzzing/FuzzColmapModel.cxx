// Fuzzes the COLMAP model reader, text and binary. The first byte picks the
// format (even: text, odd: binary); the rest holds cameras, images and
// points3D separated by "=====" lines (see splitParts).
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Video/ColmapImport.h>

#include <filesystem>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 1)
  {
    return 0;
  }
  const bool binary = (data[0] & 1) != 0;
  const std::string folder = vimlop::fuzzing::temporaryFolder("colmap");
  const std::string ext = binary ? ".bin" : ".txt";
  const std::vector<std::string_view> parts = vimlop::fuzzing::splitParts(data + 1, size - 1, 3);
  const char* const names[] = { "cameras", "images", "points3D" };
  for (int i = 0; i < 3; ++i)
  {
    vimlop::fuzzing::writeFile(folder + "/" + names[i] + ext, parts[static_cast<size_t>(i)]);
  }
  try
  {
    std::vector<std::string> warnings;
    vimlop::readColmapModel(folder,
      binary ? vimlop::ColmapFormat::Binary : vimlop::ColmapFormat::Text, {}, 0.5, &warnings);
  }
  catch (const vimlop::Error&)
  {
    // Rejecting bad input with a message is the expected outcome.
  }
  return 0;
}
