#include <vimlop/Registration/RegistrationInputConversion.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/NoiseModel.h>
#include <vimlop/Core/OrientNormalsIntoAir.h>

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkTable.h>

#include <Eigen/Geometry>

#include <map>
#include <string>

namespace vimlop
{

namespace
{

std::vector<Eigen::Vector3d> pointsOf(vtkPolyData* polyData)
{
  std::vector<Eigen::Vector3d> points(static_cast<size_t>(polyData->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < polyData->GetNumberOfPoints(); ++i)
  {
    polyData->GetPoint(i, points[static_cast<size_t>(i)].data());
  }
  return points;
}

/// Fans every polygon; with `normals` (one per cell of the polydata), turns
/// each triangle to agree with its polygon's normal.
std::vector<Eigen::Vector3i> facesOf(
  vtkPolyData* polyData, const std::vector<Eigen::Vector3d>& points, vtkDataArray* normals)
{
  std::vector<Eigen::Vector3i> faces;
  faces.reserve(static_cast<size_t>(polyData->GetNumberOfPolys()));
  // Cell data run over vertices, lines, polygons and strips, in that order.
  vtkIdType cell = polyData->GetNumberOfVerts() + polyData->GetNumberOfLines();
  auto it = vtk::TakeSmartPointer(polyData->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cell)
  {
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    it->GetCurrentCell(n, ids);
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    if (normals)
    {
      normals->GetTuple(cell, normal.data());
    }
    for (vtkIdType k = 1; k + 1 < n; ++k)
    {
      Eigen::Vector3i face(
        static_cast<int>(ids[0]), static_cast<int>(ids[k]), static_cast<int>(ids[k + 1]));
      const Eigen::Vector3d winding =
        (points[face[1]] - points[face[0]]).cross(points[face[2]] - points[face[0]]);
      if (winding.dot(normal) < 0.0)
      {
        std::swap(face[1], face[2]);
      }
      faces.push_back(face);
    }
  }
  return faces;
}

vtkDataArray* column(vtkTable* table, const char* name, int components, const std::string& what)
{
  auto* array = vtkArrayDownCast<vtkDataArray>(table->GetColumnByName(name));
  if (!array || array->GetNumberOfComponents() != components)
  {
    throw Error(what + ": missing " +
      (components == 1 ? std::string("numeric")
                       : std::to_string(components) + "-component numeric") +
      " column '" + name + "'");
  }
  return array;
}

vtkDataArray* pointArray(
  vtkPolyData* polyData, const char* name, int components, const std::string& what)
{
  auto* array = polyData->GetPointData()->GetArray(name);
  if (!array || array->GetNumberOfComponents() != components)
  {
    throw Error(what + ": missing " +
      (components == 1 ? std::string("numeric")
                       : std::to_string(components) + "-component numeric") +
      " point array '" + name + "'");
  }
  return array;
}

} // namespace

TriangleMesh toModelMesh(vtkPolyData* surface, std::string* note)
{
  if (!surface || surface->GetNumberOfPolys() == 0)
  {
    throw Error("model surface: no polygons");
  }
  vtkDataArray* normals = surface->GetCellData()->GetNormals();
  if (!normals)
  {
    normals = surface->GetCellData()->GetArray("Normals");
  }
  if (normals &&
    (normals->GetNumberOfComponents() != 3 ||
      normals->GetNumberOfTuples() != surface->GetNumberOfCells()))
  {
    throw Error(
      "model surface: the 'Normals' cell array must have 3 components and one tuple per cell");
  }
  try
  {
    if (normals)
    {
      const std::vector<Eigen::Vector3d> points = pointsOf(surface);
      std::vector<Eigen::Vector3i> faces = facesOf(surface, points, normals);
      return TriangleMesh(points, std::move(faces));
    }
    // No normals: one consistent orientation first, then into the air.
    vtkNew<vtkPolyData> polygons;
    polygons->SetPoints(surface->GetPoints());
    polygons->SetPolys(surface->GetPolys());
    vtkNew<vtkPolyDataNormals> consistent;
    consistent->SetInputData(polygons);
    consistent->ConsistencyOn();
    consistent->SplittingOff();
    consistent->AutoOrientNormalsOff();
    consistent->ComputePointNormalsOff();
    consistent->ComputeCellNormalsOn();
    consistent->Update();
    vtkPolyData* oriented = consistent->GetOutput();
    const TriangleMesh mesh = orientNormalsIntoAir(
      TriangleMesh(pointsOf(oriented), facesOf(oriented, pointsOf(oriented), nullptr)));
    const bool closed = mesh.numberOfBoundaryEdges() == 0;
    if (note)
    {
      *note = closed
        ? "the model surface has no 'Normals' cell array; computed consistent face normals "
          "pointing into the air it encloses"
        : "the model surface has no 'Normals' cell array and is open; computed consistent face "
          "normals following the vertex order of its first polygon (they must point into the air)";
    }
    return mesh;
  }
  catch (const Error& e)
  {
    throw Error(std::string("model surface: ") + e.what());
  }
}

RegistrationData toRegistrationData(
  vtkPolyData* sfmPoints, vtkTable* frames, vtkPolyData* contours, double defaultSigmaMm)
{
  if (!sfmPoints || sfmPoints->GetNumberOfPoints() == 0)
  {
    throw Error("SfM points: no points");
  }
  RegistrationData data;
  data.points = pointsOf(sfmPoints);
  vtkDataArray* covariances = sfmPoints->GetPointData()->GetArray("Covariance");
  if (covariances)
  {
    if (covariances->GetNumberOfComponents() != 9)
    {
      throw Error("SfM points: the 'Covariance' array has " +
        std::to_string(covariances->GetNumberOfComponents()) +
        " components; expected 9 (a row-major 3 x 3 matrix, mm^2)");
    }
    data.pointCovariances.resize(data.points.size());
    for (size_t i = 0; i < data.points.size(); ++i)
    {
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor> c;
      covariances->GetTuple(static_cast<vtkIdType>(i), c.data());
      data.pointCovariances[i] = c;
    }
  }
  else
  {
    if (!(defaultSigmaMm > 0.0))
    {
      throw Error("SfM points: no 'Covariance' array and no positive default sigma");
    }
    data.pointCovariances.assign(data.points.size(), isotropicCovariance(defaultSigmaMm));
  }

  std::map<int, size_t> rowOfId;
  if (frames)
  {
    const std::string what = "frame table";
    vtkDataArray* ids = column(frames, "FrameId", 1, what);
    vtkDataArray* fx = column(frames, "Fx", 1, what);
    vtkDataArray* fy = column(frames, "Fy", 1, what);
    vtkDataArray* cx = column(frames, "Cx", 1, what);
    vtkDataArray* cy = column(frames, "Cy", 1, what);
    vtkDataArray* width = column(frames, "WidthPx", 1, what);
    vtkDataArray* height = column(frames, "HeightPx", 1, what);
    vtkDataArray* poses = column(frames, "CameraToSfm", 16, what);
    for (vtkIdType row = 0; row < frames->GetNumberOfRows(); ++row)
    {
      VideoFrame frame;
      frame.frameId = static_cast<int>(ids->GetComponent(row, 0));
      if (!rowOfId.emplace(frame.frameId, data.frames.size()).second)
      {
        throw Error(what + ": frame id " + std::to_string(frame.frameId) + " appears twice");
      }
      frame.intrinsics.fx = fx->GetComponent(row, 0);
      frame.intrinsics.fy = fy->GetComponent(row, 0);
      frame.intrinsics.cx = cx->GetComponent(row, 0);
      frame.intrinsics.cy = cy->GetComponent(row, 0);
      frame.intrinsics.widthPx = static_cast<int>(width->GetComponent(row, 0));
      frame.intrinsics.heightPx = static_cast<int>(height->GetComponent(row, 0));
      Eigen::Matrix<double, 4, 4, Eigen::RowMajor> m;
      poses->GetTuple(row, m.data());
      try
      {
        frame.intrinsics.validate();
        frame.cameraToSfm = CameraPose::fromMatrix(m);
      }
      catch (const Error& e)
      {
        throw Error(what + ", row " + std::to_string(row) + ": " + e.what());
      }
      data.frames.push_back(std::move(frame));
    }
  }

  if (contours && contours->GetNumberOfPoints() > 0)
  {
    const std::string what = "video contours";
    if (!frames)
    {
      throw Error(what + ": " + std::to_string(contours->GetNumberOfPoints()) +
        " contour points but no frame table");
    }
    vtkDataArray* ids = pointArray(contours, "FrameId", 1, what);
    vtkDataArray* normals = pointArray(contours, "ContourNormal", 2, what);
    for (vtkIdType i = 0; i < contours->GetNumberOfPoints(); ++i)
    {
      const int id = static_cast<int>(ids->GetComponent(i, 0));
      const auto row = rowOfId.find(id);
      if (row == rowOfId.end())
      {
        throw Error(what + ": point " + std::to_string(i) + " belongs to frame " +
          std::to_string(id) + ", which the frame table (" + std::to_string(data.frames.size()) +
          " rows) does not have");
      }
      double p[3];
      contours->GetPoint(i, p);
      ContourPoint c;
      c.pixel = Eigen::Vector2d(p[0], p[1]);
      c.normal = Eigen::Vector2d(normals->GetComponent(i, 0), normals->GetComponent(i, 1));
      data.frames[row->second].contour.push_back(c);
    }
  }
  return data;
}

vtkSmartPointer<vtkPolyData> makeSfmPointPolyData(const RegistrationData& data)
{
  const auto n = static_cast<vtkIdType>(data.points.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkCellArray> vertices;
  vtkNew<vtkDoubleArray> covariances;
  covariances->SetName("Covariance");
  covariances->SetNumberOfComponents(9);
  covariances->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    points->SetPoint(i, data.points[static_cast<size_t>(i)].data());
    vertices->InsertNextCell(1, &i);
    if (static_cast<size_t>(i) < data.pointCovariances.size())
    {
      const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> c =
        data.pointCovariances[static_cast<size_t>(i)];
      covariances->SetTuple(i, c.data());
    }
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetVerts(vertices);
  if (data.pointCovariances.size() == data.points.size())
  {
    polyData->GetPointData()->AddArray(covariances);
  }
  return polyData;
}

vtkSmartPointer<vtkTable> makeFrameTable(const std::vector<VideoFrame>& frames)
{
  const auto n = static_cast<vtkIdType>(frames.size());
  auto makeColumn = [n](const char* name, int components)
  {
    auto array = vtkSmartPointer<vtkDoubleArray>::New();
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(n);
    return array;
  };
  vtkNew<vtkIntArray> ids;
  ids->SetName("FrameId");
  ids->SetNumberOfTuples(n);
  vtkNew<vtkIntArray> width;
  width->SetName("WidthPx");
  width->SetNumberOfTuples(n);
  vtkNew<vtkIntArray> height;
  height->SetName("HeightPx");
  height->SetNumberOfTuples(n);
  auto fx = makeColumn("Fx", 1);
  auto fy = makeColumn("Fy", 1);
  auto cx = makeColumn("Cx", 1);
  auto cy = makeColumn("Cy", 1);
  auto poses = makeColumn("CameraToSfm", 16);
  for (vtkIdType row = 0; row < n; ++row)
  {
    const VideoFrame& frame = frames[static_cast<size_t>(row)];
    ids->SetValue(row, frame.frameId);
    fx->SetValue(row, frame.intrinsics.fx);
    fy->SetValue(row, frame.intrinsics.fy);
    cx->SetValue(row, frame.intrinsics.cx);
    cy->SetValue(row, frame.intrinsics.cy);
    width->SetValue(row, frame.intrinsics.widthPx);
    height->SetValue(row, frame.intrinsics.heightPx);
    const Eigen::Matrix<double, 4, 4, Eigen::RowMajor> m = frame.cameraToSfm.matrix();
    poses->SetTuple(row, m.data());
  }
  auto table = vtkSmartPointer<vtkTable>::New();
  table->AddColumn(ids);
  table->AddColumn(fx);
  table->AddColumn(fy);
  table->AddColumn(cx);
  table->AddColumn(cy);
  table->AddColumn(width);
  table->AddColumn(height);
  table->AddColumn(poses);
  return table;
}

vtkSmartPointer<vtkPolyData> makeContourPolyData(const std::vector<VideoFrame>& frames)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> vertices;
  vtkNew<vtkIntArray> ids;
  ids->SetName("FrameId");
  vtkNew<vtkDoubleArray> normals;
  normals->SetName("ContourNormal");
  normals->SetNumberOfComponents(2);
  for (const VideoFrame& frame : frames)
  {
    for (const ContourPoint& c : frame.contour)
    {
      const vtkIdType id = points->InsertNextPoint(c.pixel.x(), c.pixel.y(), 0.0);
      vertices->InsertNextCell(1, &id);
      ids->InsertNextValue(frame.frameId);
      normals->InsertNextTuple2(c.normal.x(), c.normal.y());
    }
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetVerts(vertices);
  polyData->GetPointData()->AddArray(ids);
  polyData->GetPointData()->AddArray(normals);
  return polyData;
}

} // namespace vimlop
