#include <vimlop/Imaging/PolyDataConversion.h>

#include <vimlop/Core/Error.h>

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

namespace vimlop
{

TriangleMesh toTriangleMesh(vtkPolyData* polyData)
{
  if (!polyData || polyData->GetNumberOfPolys() == 0)
  {
    throw Error("the surface has no polygons");
  }
  std::vector<Eigen::Vector3d> vertices(static_cast<size_t>(polyData->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < polyData->GetNumberOfPoints(); ++i)
  {
    polyData->GetPoint(i, vertices[static_cast<size_t>(i)].data());
  }
  std::vector<Eigen::Vector3i> faces;
  faces.reserve(static_cast<size_t>(polyData->GetNumberOfPolys()));
  auto it = vtk::TakeSmartPointer(polyData->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    it->GetCurrentCell(n, ids);
    for (vtkIdType k = 0; k < n; ++k)
    {
      // Checked here, in vtkIdType: ids beyond int would wrap in the cast below.
      if (ids[k] < 0 || ids[k] >= polyData->GetNumberOfPoints())
      {
        throw Error("polygon " + std::to_string(it->GetCurrentCellId()) + " refers to point " +
          std::to_string(ids[k]) + " but the surface has " +
          std::to_string(polyData->GetNumberOfPoints()) + " points");
      }
    }
    // A fan keeps the polygon's orientation; airway surfaces are triangles anyway.
    for (vtkIdType k = 1; k + 1 < n; ++k)
    {
      // A triangle naming one point twice (left by decimation or point
      // merging in other tools) covers no surface: dropped, not an error.
      if (ids[0] == ids[k] || ids[k] == ids[k + 1] || ids[0] == ids[k + 1])
      {
        continue;
      }
      faces.emplace_back(
        static_cast<int>(ids[0]), static_cast<int>(ids[k]), static_cast<int>(ids[k + 1]));
    }
  }
  return TriangleMesh(std::move(vertices), std::move(faces));
}

vtkSmartPointer<vtkPolyData> toPolyData(const TriangleMesh& mesh)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.numberOfVertices());
  for (int i = 0; i < mesh.numberOfVertices(); ++i)
  {
    points->SetPoint(i, mesh.vertices()[i].data());
  }
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(mesh.numberOfFaces(), 3 * mesh.numberOfFaces());
  vtkNew<vtkDoubleArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(mesh.numberOfFaces());
  for (int f = 0; f < mesh.numberOfFaces(); ++f)
  {
    const vtkIdType ids[3] = { mesh.faces()[f][0], mesh.faces()[f][1], mesh.faces()[f][2] };
    polys->InsertNextCell(3, ids);
    normals->SetTuple(f, mesh.faceNormals()[f].data());
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetPolys(polys);
  polyData->GetCellData()->SetNormals(normals);
  return polyData;
}

} // namespace vimlop
