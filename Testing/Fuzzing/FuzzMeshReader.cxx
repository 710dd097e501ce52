// Fuzzes the mesh reader in every format it accepts, and the conversion of
// what it read to VIMLOP's triangle mesh, as every command that takes --mesh
// does: VIMLOP's checks of a file before VTK sees it (the PLY walk, legacy
// cell sizes, counts against the file size) and VTK's readers behind them.
// The first byte picks the format, the rest is the file. Seeds: the meshes of the
// bad-input corpus and small valid meshes of each format.
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>

#include <vtkObject.h>
#include <vtkPolyData.h>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  vtkObject::GlobalWarningDisplayOff(); // the reader reports errors itself
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 1)
  {
    return 0;
  }
  static const char* const suffixes[] = { ".ply", ".vtk", ".vtp", ".obj", ".stl" };
  const std::string path = vimlop::fuzzing::writeInput(data + 1, size - 1, suffixes[data[0] % 5]);
  try
  {
    vimlop::toTriangleMesh(vimlop::readPolyData(path));
  }
  catch (const vimlop::Error&)
  {
    // Rejecting bad input with a message is the expected outcome.
  }
  return 0;
}
