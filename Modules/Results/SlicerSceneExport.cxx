#include <vimlop/Results/SlicerSceneExport.h>

#include <vimlop/Results/InputIdentity.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/CoordinateFrames.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Core/TransformSequenceFile.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/LinearTransformIO.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Registration/RegistrationOutputConversion.h>
#include <vimlop/Results/RegistrationRecordIO.h>
#include <vimlop/Results/ResultFolderTransaction.h>

#include <vtkCellArray.h>
#include <vtkConeSource.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

namespace fs = std::filesystem;

namespace vimlop
{

namespace
{

AffineMatrix4 rowMajor(const Eigen::Matrix4d& matrix)
{
  AffineMatrix4 values;
  for (int i = 0; i < 16; ++i)
  {
    values[i] = matrix(i / 4, i % 4);
  }
  return values;
}

std::string frameTransformName(int frameId)
{
  char name[64];
  std::snprintf(name, sizeof(name), "CameraToCT-%04d", frameId);
  return name;
}

/// The optical centres in frame order, joined by one line.
vtkSmartPointer<vtkPolyData> cameraPath(const RegistrationResult& result)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> line;
  line->InsertNextCell(static_cast<int>(result.frames.size()));
  for (const FrameResult& frame : result.frames)
  {
    line->InsertCellPoint(points->InsertNextPoint(frame.cameraToCT.centre.data()));
  }
  auto path = vtkSmartPointer<vtkPolyData>::New();
  path->SetPoints(points);
  path->SetLines(line);
  return path;
}

/// A cone 4 mm long and 3 mm wide at its base, its apex at the optical centre
/// and opening along the optical axis (camera +z): the endoscope's tip in the
/// camera frame, which the scene moves along the path.
vtkSmartPointer<vtkPolyData> endoscopeGlyph()
{
  vtkNew<vtkConeSource> cone;
  cone->SetHeight(4.0);
  cone->SetRadius(1.5);
  cone->SetResolution(24);
  cone->SetCenter(0.0, 0.0, 2.0);
  cone->SetDirection(0.0, 0.0, -1.0);
  cone->Update();
  return cone->GetOutput();
}

/// One MRML node: its tag and attributes, in order.
std::string node(
  const std::string& tag, const std::vector<std::pair<std::string, std::string>>& attributes)
{
  std::string xml = " <" + tag;
  for (const auto& [name, value] : attributes)
  {
    xml += "\n  " + name + "=\"" + escapeHtml(value) + "\"";
  }
  return xml + "></" + tag + ">\n";
}

/// A model with its storage (a legacy VTK file, LPS) and display nodes.
std::string modelNodes(const std::string& id, const std::string& name, const std::string& color,
  double opacity, const std::string& representation, const std::string& transformId)
{
  const std::string storage = "vtkMRMLModelStorageNode" + id;
  const std::string display = "vtkMRMLModelDisplayNode" + id;
  std::string references = "display:" + display + ";storage:" + storage + ";";
  if (!transformId.empty())
  {
    references = "transform:" + transformId + ";" + references;
  }
  return node("ModelStorage",
           { { "id", storage }, { "name", name + "Storage" }, { "fileName", name + ".vtk" },
             { "coordinateSystem", "LPS" } }) +
    node("ModelDisplay",
      { { "id", display }, { "name", name + "Display" }, { "color", color },
        { "opacity", std::to_string(opacity) }, { "representation", representation },
        { "pointSize", "3" }, { "lineWidth", "2" }, { "visibility", "true" },
        { "sliceIntersectionVisibility", "true" } }) +
    node("Model",
      { { "id", "vtkMRMLModelNode" + id }, { "name", name }, { "references", references } });
}

/**
 * The scene: the CT, the models, the camera transform (the sequence's proxy)
 * moving the endoscope glyph, the camera-to-CT sequence read from its file,
 * and the browser that plays it. Node tags and references are those of
 * Slicer 5's MRML scenes; ids are local to the file.
 */
std::string slicerSceneXml(const std::string& ctFile)
{
  // A Slicer 5 scene: Slicer reads the meshes of an older one (version
  // "Slicer4.4.0", or none) as RAS unless their files say otherwise (ours
  // say SPACE=LPS anyway).
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                    "<MRML version=\"Slicer 5.0.0 1\" userTags=\"\">\n";
  if (!ctFile.empty())
  {
    xml += node("VolumeArchetypeStorage",
      { { "id", "vtkMRMLVolumeArchetypeStorageNode1" }, { "name", "CTStorage" },
        { "fileName", ctFile }, { "useCompression", "1" } });
    xml += node("VolumeDisplay",
      { { "id", "vtkMRMLScalarVolumeDisplayNode1" }, { "name", "CTDisplay" },
        { "colorNodeID", "vtkMRMLColorTableNodeGrey" }, { "autoWindowLevel", "0" },
        { "window", "2000" }, { "level", "0" }, { "interpolate", "1" } });
    xml += node("Volume",
      { { "id", "vtkMRMLScalarVolumeNode1" }, { "name", "CT" },
        { "references",
          "display:vtkMRMLScalarVolumeDisplayNode1;storage:"
          "vtkMRMLVolumeArchetypeStorageNode1;" } });
  }
  xml += modelNodes("1", "Airway", "0.9 0.7 0.6", 0.4, "2", "");
  xml += modelNodes("2", "RegisteredPoints", "0.2 0.9 0.2", 1.0, "0", "");
  xml += modelNodes("3", "CameraPath", "1 1 0", 1.0, "1", "");
  xml += modelNodes("4", "Endoscope", "0.2 0.6 1", 1.0, "2", "vtkMRMLLinearTransformNode1");
  // The proxy: the browser sets it to the selected item of the sequence.
  xml +=
    node("LinearTransform", { { "id", "vtkMRMLLinearTransformNode1" }, { "name", "CameraToCT" } });
  xml += node("LinearTransformSequenceStorage",
    { { "id", "vtkMRMLLinearTransformSequenceStorageNode1" },
      { "name", "CameraToCTSequenceStorage" }, { "fileName", "CameraToCT.seq.mha" } });
  xml += node("Sequence",
    { { "id", "vtkMRMLSequenceNode1" }, { "name", "CameraToCT-Sequence" }, { "indexName", "time" },
      { "indexUnit", "s" }, { "indexType", "numeric" },
      { "references", "storage:vtkMRMLLinearTransformSequenceStorageNode1;" } });
  xml += node("SequenceBrowser",
    { { "id", "vtkMRMLSequenceBrowserNode1" }, { "name", "CameraPath" },
      { "playbackActive", "false" }, { "playbackRateFps", "10" }, { "playbackLooped", "true" },
      { "selectedItemNumber", "0" }, { "virtualNodePostfixes", "0" },
      { "SynchronizationPropertiesMap0",
        "playback true recording false overwriteProxyName false saveChanges false" },
      { "references",
        "sequenceNodeRef0:vtkMRMLSequenceNode1;dataNodeRef0:vtkMRMLLinearTransformNode1;" } });
  return xml + "</MRML>\n";
}

} // namespace

SlicerSceneFiles writeSlicerScene(
  const RegistrationRecord& record, const std::string& folder, const SlicerSceneOptions& options)
{
  const RegistrationResult& result = record.result;
  if (result.frames.empty())
  {
    throw Error("the result has no frames: there is no camera pose to export");
  }
  const std::string& extension = options.transformExtension;
  if (!isLinearTransformPath("x" + extension))
  {
    throw Error("'" + extension +
      "' is not the extension of an ITK transform file (expected .tfm, .txt, .h5, .hdf5 or .mat)");
  }
  const auto progress = [&options](const std::string& step)
  {
    if (options.onProgress)
    {
      options.onProgress(step);
    }
  };
  const fs::path dir(folder);
  SlicerSceneFiles written;
  written.files.push_back("Scene.mrml");
  const auto add = [&written](const std::string& name) { written.files.push_back(name); };

  std::string ctFile;
  const std::string ctPath = options.ctPath.empty() && options.ctFromResult
    ? recordedInputPath(record, "ct")
    : options.ctPath;
  if (!ctPath.empty())
  {
    progress("reading the CT " + ctPath);
    const CTVolume ct = readCTVolume(ctPath);
    progress("writing CT.nrrd");
    writeCTVolume(ct, (dir / "CT.nrrd").string());
    add("CT.nrrd");
    ctFile = "CT.nrrd";
    written.withCT = true;
  }

  progress("writing the models");
  writePolyData(toPolyData(record.model), (dir / "Airway.vtk").string());
  add("Airway.vtk");
  writePolyData(
    makeRegisteredPointPolyData(record.data, result), (dir / "RegisteredPoints.vtk").string());
  add("RegisteredPoints.vtk");
  writePolyData(cameraPath(result), (dir / "CameraPath.vtk").string());
  add("CameraPath.vtk");
  writePolyData(endoscopeGlyph(), (dir / "Endoscope.vtk").string());
  add("Endoscope.vtk");

  progress("writing the camera sequence and the ITK transform files");
  std::vector<TimedTransform> sequence;
  // Times are kept per data frame; the result's frames are those with a pose.
  std::map<int, double> timeOfFrame;
  if (record.frameTimesS.size() == record.data.frames.size())
  {
    for (size_t i = 0; i < record.data.frames.size(); ++i)
    {
      timeOfFrame[record.data.frames[i].frameId] = record.frameTimesS[i];
    }
  }
  const bool timed = std::all_of(result.frames.begin(), result.frames.end(),
    [&](const FrameResult& frame) { return timeOfFrame.count(frame.frameId) > 0; });
  fs::create_directories(dir / "Transforms");
  // ITK's resampling form: "AToB" is stored as B to A (see the file's comment).
  writeLinearTransformFile(rowMajor(result.sfmToCT.inverse().matrix()),
    (dir / "Transforms" / ("SfMToCT" + extension)).string());
  add("Transforms/SfMToCT" + extension);
  for (size_t i = 0; i < result.frames.size(); ++i)
  {
    const FrameResult& frame = result.frames[i];
    const Eigen::Matrix4d cameraToCT = frame.cameraToCT.matrix();
    const std::string name = "Transforms/" + frameTransformName(frame.frameId) + extension;
    writeLinearTransformFile(rowMajor(cameraToCT.inverse()), (dir / name).string());
    add(name);
    // Slicer shows a sequence item as it is: the camera-to-CT map into RAS.
    sequence.push_back(
      { timed ? timeOfFrame.at(frame.frameId) : static_cast<double>(i), intoRas(cameraToCT) });
  }
  writeTransformSequenceFile(sequence, "CameraToCT", (dir / "CameraToCT.seq.mha").string());
  add("CameraToCT.seq.mha");
  written.frames = static_cast<int>(result.frames.size());

  progress("writing Scene.mrml");
  writeFileAtomically((dir / "Scene.mrml").string(), slicerSceneXml(ctFile));

  nlohmann::json manifest = {
    { "format", "vimlop-export" },
    { "version", 1 },
    { "source", record.source },
    { "files", written.files },
    { "conventions",
      { { "meshes", "LPS, mm (CT frame)" },
        { "transform_files",
          "ITK resampling form: a file named AToB holds the map from B points to A points, LPS" },
        { "sequence", "CameraToCT: camera (x right, y down, z forward) to RAS, mm, per frame" } } },
    { "frames", written.frames },
    { "sequence_index", timed ? "frame time, s" : "frame number (the result has no frame times)" },
  };
  add("vimlop-export.json");
  writeFileAtomically((dir / "vimlop-export.json").string(), manifest.dump(2) + "\n");
  return written;
}

SlicerSceneFiles exportResultForSlicer(const std::string& resultFolder,
  const std::string& exportFolder, bool replace, const SlicerSceneOptions& options)
{
  const RegistrationRecord record = readRegistrationRecord(resultFolder);
  // The transaction replaces result folders too (for --force of `register`):
  // an export must never take the place of a registration's result.
  std::error_code error;
  const fs::path out(exportFolder);
  if (fs::exists(out / "result.json", error) || fs::exists(out / "registered-poses.json", error))
  {
    throwFileError(exportFolder,
      "is a registration result folder; an export never replaces one (choose another --out)");
  }
  ResultFolderTransaction transaction(exportFolder,
    replace ? ResultFolderTransaction::Existing::Replace
            : ResultFolderTransaction::Existing::Refuse);
  const SlicerSceneFiles files = writeSlicerScene(record, transaction.stagingFolder(), options);
  transaction.commit();
  return files;
}

} // namespace vimlop
