#include <vimlop/Imaging/MeshIO.h>

#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/LegacyVtkFileCheck.h>
#include <vimlop/Imaging/MeshFileChecks.h>
#include <vimlop/Imaging/PlyMeshReader.h>
#include <vimlop/Imaging/VtkXmlFileCheck.h>

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYWriter.h>
#include <vtkPoints.h>
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

/// Runs a VTK reader and turns its silent failures into an exception.
template <typename Reader>
vtkSmartPointer<vtkPolyData> runReader(Reader* reader, const std::string& path)
{
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* output = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || !output || output->GetNumberOfPoints() == 0)
  {
    throwFileError(path, "not a readable mesh (no points could be read)");
  }
  vtkSmartPointer<vtkPolyData> mesh = output;
  return mesh;
}

/// What VIMLOP's PLY reader read, as VTK's reader would have returned it.
vtkSmartPointer<vtkPolyData> toPolyData(const std::string& path, const detail::PlyMesh& ply)
{
  if (ply.points.empty())
  {
    throwFileError(path, "not a readable mesh (no points could be read)");
  }
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints(static_cast<vtkIdType>(ply.points.size()));
  for (std::size_t i = 0; i < ply.points.size(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), ply.points[i].data());
  }
  vtkNew<vtkCellArray> polys;
  for (const std::vector<std::int64_t>& face : ply.faces)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(face.size()));
    for (std::int64_t id : face)
    {
      polys->InsertCellPoint(static_cast<vtkIdType>(id));
    }
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}

} // namespace

bool isMeshPath(const std::string& path)
{
  const std::string ext = lowerCaseExtension(path);
  return ext == ".vtp" || ext == ".vtk" || ext == ".stl" || ext == ".ply" || ext == ".obj";
}

bool isWritableMeshPath(const std::string& path)
{
  const std::string ext = lowerCaseExtension(path);
  return ext == ".vtp" || ext == ".vtk" || ext == ".stl" || ext == ".ply";
}

vtkSmartPointer<vtkPolyData> readPolyData(const std::string& path)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
  {
    throwFileError(path, "no such file");
  }
  const std::string ext = lowerCaseExtension(path);
  if (ext == ".vtp")
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    // The XML reader reports parse errors through its own error observer.
    reader->SetFileName(path.c_str());
    if (!reader->CanReadFile(path.c_str()))
    {
      throwFileError(path, "not a VTK XML polydata file");
    }
    detail::checkXmlPolyData(path);
    detail::checkXmlArrays(path);
    return runReader(reader.Get(), path);
  }
  if (ext == ".vtk")
  {
    vtkNew<vtkPolyDataReader> reader;
    reader->SetFileName(path.c_str());
    if (!reader->IsFilePolyData())
    {
      throwFileError(path, "not a legacy VTK polydata file");
    }
    detail::checkLegacyVtk(path);
    return runReader(reader.Get(), path);
  }
  if (ext == ".stl")
  {
    detail::checkStl(path);
    vtkNew<vtkSTLReader> reader;
    return runReader(reader.Get(), path);
  }
  if (ext == ".ply")
  {
    return toPolyData(path, detail::readPlyMesh(path));
  }
  if (ext == ".obj")
  {
    detail::checkObj(path);
    vtkNew<vtkOBJReader> reader;
    return runReader(reader.Get(), path);
  }
  throwFileError(path, "unsupported mesh file type (expected .vtp, .vtk, .stl, .ply or .obj)");
}

void writePolyData(vtkPolyData* mesh, const std::string& path)
{
  const std::string ext = lowerCaseExtension(path);
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
    // VIMLOP's meshes are in the CT frame, LPS; 3D Slicer reads the frame of
    // a legacy VTK file from this tag in its header.
    writer->SetHeader("VIMLOP mesh SPACE=LPS");
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
    throwFileError(path, "unsupported mesh output type (expected .vtp, .vtk, .stl or .ply)");
  }
  if (!ok)
  {
    throwFileError(path, "could not write the mesh");
  }
}

} // namespace vimlop
