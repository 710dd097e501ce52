#include <vimlop/Imaging/MeshIO.h>

#include <vimlop/Core/Error.h>

#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPLYWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLReader.h>
#include <vtkSTLWriter.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace vimlop
{

namespace
{

std::string extensionOf(const std::string& path)
{
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(
    ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw Error("'" + path + "': " + problem);
}

/// Runs a VTK reader and turns its silent failures into an exception.
template <typename Reader>
vtkSmartPointer<vtkPolyData> runReader(Reader* reader, const std::string& path)
{
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* output = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || !output || output->GetNumberOfPoints() == 0)
  {
    fail(path, "not a readable mesh (no points could be read)");
  }
  vtkSmartPointer<vtkPolyData> mesh = output;
  return mesh;
}

/// VIMLOP's surfaces have 10^4 to 10^6 triangles; a file that promises more
/// points or cells than this is corrupt or not meant for VIMLOP, and VTK's
/// readers would allocate what it promises before noticing.
constexpr std::uint64_t maxMeshElements = 20000000;

void checkPromise(const std::string& path, std::uint64_t count, const std::string& what)
{
  if (count > maxMeshElements)
  {
    fail(path,
      "the file promises " + std::to_string(count) + " " + what + "; meshes with more than " +
        std::to_string(maxMeshElements) + " are refused");
  }
}

/// Legacy VTK: the counts after POINTS, POLYGONS and the like, wherever they
/// are in the file (ASCII or binary data between them).
void checkLegacyVtk(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  while (std::getline(in, line))
  {
    std::istringstream words(line);
    std::string keyword;
    std::uint64_t count = 0;
    if (!(words >> keyword) || keyword.empty() ||
      !std::isupper(static_cast<unsigned char>(keyword[0])))
    {
      continue;
    }
    if (keyword == "POINTS" && (words >> count))
    {
      checkPromise(path, count, "points");
    }
    else if ((keyword == "VERTICES" || keyword == "LINES" || keyword == "POLYGONS" ||
               keyword == "TRIANGLE_STRIPS") &&
      (words >> count))
    {
      checkPromise(path, count, "cells");
      std::uint64_t size = 0;
      if (words >> size)
      {
        // Every cell lists at least one point id, besides its size or offset.
        checkPromise(path, size / 4, "cells (" + std::to_string(size) + " cell ids)");
      }
    }
    else if ((keyword == "POINT_DATA" || keyword == "CELL_DATA") && (words >> count))
    {
      checkPromise(path, count, "data values");
    }
  }
}

/// VTK XML: the counts in the attributes of the Piece elements.
void checkXmlPolyData(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string head(1 << 16, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  for (const char* attribute : { "NumberOfPoints=\"", "NumberOfVerts=\"", "NumberOfLines=\"",
         "NumberOfStrips=\"", "NumberOfPolys=\"" })
  {
    for (size_t at = head.find(attribute); at != std::string::npos;
         at = head.find(attribute, at + 1))
    {
      const size_t digits = at + std::strlen(attribute);
      std::uint64_t count = 0;
      size_t i = digits;
      for (;
           i < head.size() && i < digits + 19 && std::isdigit(static_cast<unsigned char>(head[i]));
           ++i)
      {
        count = count * 10 + static_cast<std::uint64_t>(head[i] - '0');
      }
      const std::string name(attribute + 8, std::strlen(attribute) - 10);
      checkPromise(path, count, name == "Points" ? "points" : "cells (" + name + ")");
    }
  }
}

/// VTK's STL reader accepts a binary file shorter than its triangle count
/// says; check the count against the size first (binary STL: an 80-byte
/// header, a 4-byte count, 50 bytes per triangle).
void checkStl(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  char start[84] = {};
  in.read(start, sizeof(start));
  const std::streamsize got = in.gcount();
  const std::uint64_t size = std::filesystem::file_size(path);
  if (got < 84)
  {
    if (got >= 5 && std::strncmp(start, "solid", 5) == 0)
    {
      return; // a short ASCII file: VTK's reader judges it
    }
    fail(path, "not an STL file (too short)");
  }
  std::uint32_t count = 0;
  for (int i = 3; i >= 0; --i)
  {
    count = count << 8 | static_cast<unsigned char>(start[80 + i]);
  }
  const std::uint64_t binarySize = 84 + 50 * static_cast<std::uint64_t>(count);
  if (binarySize == size || std::strncmp(start, "solid", 5) == 0)
  {
    return; // a consistent binary file, or ASCII
  }
  fail(path,
    "truncated or corrupt binary STL (" + std::to_string(count) + " triangles need " +
      std::to_string(binarySize) + " bytes, the file has " + std::to_string(size) + ")");
}

/// VTK's PLY reader allocates what the header's element counts promise and
/// can crash on a huge count; each element needs at least one byte, so a
/// count above the file size is a lie.
void checkPly(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  const std::uint64_t size = std::filesystem::file_size(path);
  std::string line;
  for (int lines = 0; lines < 1000 && std::getline(in, line); ++lines)
  {
    if (line.rfind("end_header", 0) == 0)
    {
      return;
    }
    std::istringstream words(line);
    std::string keyword;
    std::string name;
    std::uint64_t count = 0;
    if ((words >> keyword >> name >> count) && keyword == "element" && count > size)
    {
      fail(path,
        "the PLY header promises " + std::to_string(count) + " " + name + " elements in a " +
          std::to_string(size) + "-byte file");
    }
  }
  fail(path, "not a PLY file (no end_header)");
}

} // namespace

bool isMeshPath(const std::string& path)
{
  const std::string ext = extensionOf(path);
  return ext == ".vtp" || ext == ".vtk" || ext == ".stl" || ext == ".ply" || ext == ".obj";
}

bool isWritableMeshPath(const std::string& path)
{
  const std::string ext = extensionOf(path);
  return ext == ".vtp" || ext == ".vtk" || ext == ".stl" || ext == ".ply";
}

vtkSmartPointer<vtkPolyData> readPolyData(const std::string& path)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
  {
    fail(path, "no such file");
  }
  const std::string ext = extensionOf(path);
  if (ext == ".vtp")
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    // The XML reader reports parse errors through its own error observer.
    reader->SetFileName(path.c_str());
    if (!reader->CanReadFile(path.c_str()))
    {
      fail(path, "not a VTK XML polydata file");
    }
    checkXmlPolyData(path);
    return runReader(reader.Get(), path);
  }
  if (ext == ".vtk")
  {
    vtkNew<vtkPolyDataReader> reader;
    reader->SetFileName(path.c_str());
    if (!reader->IsFilePolyData())
    {
      fail(path, "not a legacy VTK polydata file");
    }
    checkLegacyVtk(path);
    return runReader(reader.Get(), path);
  }
  if (ext == ".stl")
  {
    checkStl(path);
    vtkNew<vtkSTLReader> reader;
    return runReader(reader.Get(), path);
  }
  if (ext == ".ply")
  {
    vtkNew<vtkPLYReader> reader;
    if (!reader->CanReadFile(path.c_str()))
    {
      fail(path, "not a PLY file");
    }
    checkPly(path);
    return runReader(reader.Get(), path);
  }
  if (ext == ".obj")
  {
    vtkNew<vtkOBJReader> reader;
    return runReader(reader.Get(), path);
  }
  fail(path, "unsupported mesh file type (expected .vtp, .vtk, .stl, .ply or .obj)");
}

void writePolyData(vtkPolyData* mesh, const std::string& path)
{
  const std::string ext = extensionOf(path);
  int ok = 0;
  if (ext == ".vtp")
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(mesh);
    writer->SetFileName(path.c_str());
    writer->SetDataModeToAppended();
    writer->SetCompressorTypeToZLib();
    ok = writer->Write();
  }
  else if (ext == ".vtk")
  {
    vtkNew<vtkPolyDataWriter> writer;
    writer->SetInputData(mesh);
    writer->SetFileName(path.c_str());
    writer->SetFileTypeToBinary();
    ok = writer->Write();
  }
  else if (ext == ".stl")
  {
    vtkNew<vtkSTLWriter> writer;
    writer->SetInputData(mesh);
    writer->SetFileName(path.c_str());
    writer->SetFileTypeToBinary();
    ok = writer->Write();
  }
  else if (ext == ".ply")
  {
    vtkNew<vtkPLYWriter> writer;
    writer->SetInputData(mesh);
    writer->SetFileName(path.c_str());
    writer->SetFileTypeToBinary();
    ok = writer->Write();
  }
  else
  {
    fail(path, "unsupported mesh output type (expected .vtp, .vtk, .stl or .ply)");
  }
  if (!ok)
  {
    fail(path, "could not write the mesh");
  }
}

} // namespace vimlop
