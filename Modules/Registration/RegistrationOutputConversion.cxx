#include <vimlop/Registration/RegistrationOutputConversion.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Registration/CameraPoseTable.h>

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
#include <vtkTable.h>
#include <vtkUnsignedCharArray.h>

#include <map>
#include <string>

namespace vimlop
{

namespace
{

vtkSmartPointer<vtkIntArray> intColumn(const char* name, vtkIdType n)
{
  auto array = vtkSmartPointer<vtkIntArray>::New();
  array->SetName(name);
  array->SetNumberOfTuples(n);
  return array;
}

vtkSmartPointer<vtkDoubleArray> doubleColumn(const char* name, vtkIdType n)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfTuples(n);
  return array;
}

vtkDataArray* requireArray(
  vtkFieldData* data, const char* name, int components, const std::string& what)
{
  vtkDataArray* array = data->GetArray(name);
  if (!array || array->GetNumberOfComponents() != components)
  {
    throw Error(
      what + ": missing " + std::to_string(components) + "-component array '" + name + "'");
  }
  return array;
}

} // namespace

vtkSmartPointer<vtkPolyData> makeRegisteredPointPolyData(
  const RegistrationData& data, const RegistrationResult& result)
{
  const auto n = static_cast<vtkIdType>(data.points.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkCellArray> vertices;
  vtkNew<vtkDoubleArray> sfm;
  sfm->SetName("SfmPosition");
  sfm->SetNumberOfComponents(3);
  sfm->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> inlier;
  inlier->SetName("Inlier");
  inlier->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> matched;
  matched->SetName("MatchedModelPoint");
  matched->SetNumberOfComponents(3);
  matched->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const auto k = static_cast<size_t>(i);
    const Eigen::Vector3d y = result.sfmToCT.apply(data.points[k]);
    points->SetPoint(i, y.data());
    vertices->InsertNextCell(1, &i);
    sfm->SetTuple(i, data.points[k].data());
    inlier->SetValue(i, k < result.pointInliers.size() ? result.pointInliers[k] : 0);
    const Eigen::Vector3d m = k < result.pointMatches.size() ? result.pointMatches[k] : y;
    matched->SetTuple(i, m.data());
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetVerts(vertices);
  polyData->GetPointData()->AddArray(sfm);
  polyData->GetPointData()->AddArray(inlier);
  polyData->GetPointData()->AddArray(matched);
  return polyData;
}

vtkSmartPointer<vtkTable> makeFrameResultTable(const RegistrationResult& result)
{
  std::vector<FramePose> poses;
  for (const FrameResult& frame : result.frames)
  {
    poses.push_back({ frame.frameId, frame.cameraToCT });
  }
  vtkSmartPointer<vtkTable> table = makeCameraPoseTable(poses);
  const auto n = static_cast<vtkIdType>(result.frames.size());
  auto contourPoints = intColumn("ContourPoints", n);
  auto matched = intColumn("MatchedContourPoints", n);
  auto inliers = intColumn("InlierContourPoints", n);
  auto visible = intColumn("VisibleModelSamples", n);
  auto error = doubleColumn("ContourErrorPx", n);
  auto errorInliers = doubleColumn("ContourErrorInliersPx", n);
  for (vtkIdType row = 0; row < n; ++row)
  {
    const FrameResult& frame = result.frames[static_cast<size_t>(row)];
    contourPoints->SetValue(row, frame.contourPoints);
    matched->SetValue(row, frame.matched);
    inliers->SetValue(row, frame.inliers);
    visible->SetValue(row, frame.visibleModelSamples);
    error->SetValue(row, frame.contourErrorPx);
    errorInliers->SetValue(row, frame.contourErrorInliersPx);
  }
  table->AddColumn(contourPoints);
  table->AddColumn(matched);
  table->AddColumn(inliers);
  table->AddColumn(visible);
  table->AddColumn(error);
  table->AddColumn(errorInliers);
  return table;
}

vtkSmartPointer<vtkPolyData> makeCorrespondencePolyData(const RegistrationResult& result)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkIntArray> frameIds;
  frameIds->SetName("FrameId");
  vtkNew<vtkIntArray> videoIndices;
  videoIndices->SetName("VideoIndex");
  vtkNew<vtkUnsignedCharArray> inliers;
  inliers->SetName("Inlier");
  vtkNew<vtkDoubleArray> modelPoints;
  modelPoints->SetName("ModelPoint");
  modelPoints->SetNumberOfComponents(3);
  for (const FrameResult& frame : result.frames)
  {
    for (const ContourCorrespondence& c : frame.correspondences)
    {
      const vtkIdType ends[2] = { points->InsertNextPoint(c.videoPixel.x(), c.videoPixel.y(), 0.0),
        points->InsertNextPoint(c.modelPixel.x(), c.modelPixel.y(), 0.0) };
      lines->InsertNextCell(2, ends);
      frameIds->InsertNextValue(frame.frameId);
      videoIndices->InsertNextValue(c.video);
      inliers->InsertNextValue(c.inlier ? 1 : 0);
      modelPoints->InsertNextTuple(c.modelPoint.data());
    }
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetLines(lines);
  polyData->GetCellData()->AddArray(frameIds);
  polyData->GetCellData()->AddArray(videoIndices);
  polyData->GetCellData()->AddArray(inliers);
  polyData->GetCellData()->AddArray(modelPoints);
  return polyData;
}

void readRegisteredPoints(vtkPolyData* points, int expectedPoints, RegistrationResult& result)
{
  const std::string what = "registered points";
  if (!points || points->GetNumberOfPoints() != expectedPoints)
  {
    throw Error(what + ": expected " + std::to_string(expectedPoints) + " points, found " +
      std::to_string(points ? points->GetNumberOfPoints() : 0));
  }
  vtkDataArray* inliers = requireArray(points->GetPointData(), "Inlier", 1, what);
  vtkDataArray* matched = requireArray(points->GetPointData(), "MatchedModelPoint", 3, what);
  result.pointInliers.resize(static_cast<size_t>(expectedPoints));
  result.pointMatches.resize(static_cast<size_t>(expectedPoints));
  for (vtkIdType i = 0; i < expectedPoints; ++i)
  {
    result.pointInliers[static_cast<size_t>(i)] = inliers->GetComponent(i, 0) != 0.0 ? 1 : 0;
    matched->GetTuple(i, result.pointMatches[static_cast<size_t>(i)].data());
  }
}

void readCorrespondences(vtkPolyData* correspondences, RegistrationResult& result)
{
  const std::string what = "contour correspondences";
  if (!correspondences)
  {
    throw Error(what + ": no data");
  }
  std::map<int, FrameResult*> frames;
  for (FrameResult& frame : result.frames)
  {
    frame.correspondences.clear();
    frames[frame.frameId] = &frame;
  }
  if (correspondences->GetNumberOfLines() == 0)
  {
    return;
  }
  vtkCellData* cells = correspondences->GetCellData();
  vtkDataArray* frameIds = requireArray(cells, "FrameId", 1, what);
  vtkDataArray* videoIndices = requireArray(cells, "VideoIndex", 1, what);
  vtkDataArray* inliers = requireArray(cells, "Inlier", 1, what);
  vtkDataArray* modelPoints = requireArray(cells, "ModelPoint", 3, what);
  // Cell data run over vertices before lines.
  vtkIdType cell = correspondences->GetNumberOfVerts();
  auto it = vtk::TakeSmartPointer(correspondences->GetLines()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cell)
  {
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    it->GetCurrentCell(n, ids);
    const int frameId = static_cast<int>(frameIds->GetComponent(cell, 0));
    const auto frame = frames.find(frameId);
    if (n != 2 || frame == frames.end())
    {
      throw Error(what + ": line " + std::to_string(cell) + " is not a pair of a known frame");
    }
    ContourCorrespondence c;
    c.video = static_cast<int>(videoIndices->GetComponent(cell, 0));
    c.inlier = inliers->GetComponent(cell, 0) != 0.0;
    double a[3], b[3];
    correspondences->GetPoint(ids[0], a);
    correspondences->GetPoint(ids[1], b);
    c.videoPixel = Eigen::Vector2d(a[0], a[1]);
    c.modelPixel = Eigen::Vector2d(b[0], b[1]);
    modelPoints->GetTuple(cell, c.modelPoint.data());
    frame->second->correspondences.push_back(c);
  }
}

} // namespace vimlop
