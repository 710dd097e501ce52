#include "ReportFixture.h"
#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/CoordinateFrames.h>
#include <vimlop/Core/TransformSequenceFile.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/LinearTransformIO.h>
#include <vimlop/Results/RegistrationRecordIO.h>
#include <vimlop/Results/SlicerSceneExport.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <regex>
#include <set>

using namespace vimlop;
using vimlop::fixtures::errorMessageOf;

namespace
{

/// The fixture's record, its frames timed at 25 fps from 3.2 s on.
RegistrationRecord timedRecord()
{
  RegistrationRecord record = fixtures::makeReportRecord();
  for (size_t i = 0; i < record.data.frames.size(); ++i)
  {
    record.frameTimesS.push_back(3.2 + static_cast<double>(i) / 25.0);
  }
  return record;
}

Eigen::Matrix4d fromRowMajor(const AffineMatrix4& values)
{
  Eigen::Matrix4d matrix;
  for (int i = 0; i < 16; ++i)
  {
    matrix(i / 4, i % 4) = values[i];
  }
  return matrix;
}

std::string transformFile(const std::string& folder, int frameId, const std::string& extension)
{
  char name[64];
  std::snprintf(name, sizeof(name), "/Transforms/CameraToCT-%04d", frameId);
  return folder + name + extension;
}

} // namespace

TEST(SlicerSceneExport, WritesEveryPoseAsAnItkTransformFileThatReadsBackToThePose)
{
  const RegistrationRecord record = timedRecord();
  for (const std::string extension : { ".tfm", ".h5" })
  {
    SCOPED_TRACE(extension);
    const std::string dir =
      fixtures::freshTestFolder("slicer-export-itk" + extension.substr(1)).string();
    SlicerSceneOptions options;
    options.transformExtension = extension;
    const SlicerSceneFiles files = writeSlicerScene(record, dir, options);
    EXPECT_EQ(files.frames, static_cast<int>(record.result.frames.size()));
    for (const FrameResult& frame : record.result.frames)
    {
      // The file holds ITK's resampling direction, CT to camera: its inverse is the pose.
      const Eigen::Matrix4d ctToCamera =
        fromRowMajor(readLinearTransformFile(transformFile(dir, frame.frameId, extension)));
      EXPECT_LT((ctToCamera.inverse() - frame.cameraToCT.matrix()).cwiseAbs().maxCoeff(), 1e-9);
      EXPECT_LT(
        (ctToCamera * frame.cameraToCT.matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-12);
    }
    const Eigen::Matrix4d ctToSfm =
      fromRowMajor(readLinearTransformFile(dir + "/Transforms/SfMToCT" + extension));
    EXPECT_LT((ctToSfm.inverse() - record.result.sfmToCT.matrix()).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(SlicerSceneExport, TheSequenceHoldsEachCameraToRasPoseAtItsFrameTime)
{
  const RegistrationRecord record = timedRecord();
  const std::string dir = fixtures::freshTestFolder("slicer-export-sequence").string();
  writeSlicerScene(record, dir, SlicerSceneOptions());
  const std::vector<TimedTransform> items =
    readTransformSequenceFile(dir + "/CameraToCT.seq.mha", "CameraToCT");
  ASSERT_EQ(items.size(), record.result.frames.size());
  for (size_t i = 0; i < items.size(); ++i)
  {
    EXPECT_EQ(items[i].timeS, record.frameTimesS[i]);
    const Eigen::Matrix4d cameraToRas = lpsRasFlip() * record.result.frames[i].cameraToCT.matrix();
    EXPECT_EQ(items[i].matrix, cameraToRas);
  }
}

TEST(SlicerSceneExport, TheSceneNamesOnlyFilesThatAreThereAndNodesThatItHolds)
{
  const std::string dir = fixtures::freshTestFolder("slicer-export-scene").string();
  // A CT of 4 x 5 x 6 voxels, so that the scene has a volume too.
  CTVolume ct;
  ct.dims = { 4, 5, 6 };
  ct.spacingMm = { 0.5, 0.5, 1.0 };
  ct.originMm = { -10.0, 20.0, 5.0 };
  ct.intensities.assign(ct.numberOfVoxels(), -1000.0f);
  writeCTVolume(ct, dir + "-ct.nii.gz");
  SlicerSceneOptions options;
  options.ctPath = dir + "-ct.nii.gz";
  std::vector<std::string> steps;
  options.onProgress = [&steps](const std::string& step) { steps.push_back(step); };
  const SlicerSceneFiles files = writeSlicerScene(timedRecord(), dir, options);
  EXPECT_TRUE(files.withCT);
  EXPECT_GE(steps.size(), 4u);
  for (const std::string& file : files.files)
  {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + file)) << file;
  }
  const CTVolume written = readCTVolume(dir + "/CT.nrrd");
  EXPECT_EQ(written.dims, ct.dims);
  EXPECT_EQ(written.originMm, ct.originMm);

  const std::string scene = readWholeFile(dir + "/Scene.mrml");
  std::set<std::string> ids;
  const std::regex idPattern("\\bid=\"([^\"]+)\"");
  for (std::sregex_iterator it(scene.begin(), scene.end(), idPattern), end; it != end; ++it)
  {
    EXPECT_TRUE(ids.insert((*it)[1]).second) << "two nodes are " << (*it)[1];
  }
  const std::regex referencePattern("[A-Za-z0-9]+:(vtkMRML[A-Za-z]+[0-9]+);");
  int references = 0;
  for (std::sregex_iterator it(scene.begin(), scene.end(), referencePattern), end; it != end; ++it)
  {
    EXPECT_EQ(ids.count((*it)[1]), 1u)
      << "a reference to a node the scene does not hold: " << (*it)[1];
    ++references;
  }
  EXPECT_GE(references, 14);
  const std::regex filePattern("fileName=\"([^\"]+)\"");
  int fileNames = 0;
  for (std::sregex_iterator it(scene.begin(), scene.end(), filePattern), end; it != end; ++it)
  {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + (*it)[1].str())) << (*it)[1];
    ++fileNames;
  }
  EXPECT_EQ(fileNames, 6); // the CT, four models and the camera sequence
  EXPECT_NE(scene.find("name=\"CameraToCT\""), std::string::npos);
  EXPECT_NE(readWholeFile(dir + "/Airway.vtk").find("SPACE=LPS"), std::string::npos);
}

TEST(SlicerSceneExport, RefusesAResultWithoutFramesAndATransformFormatItkDoesNotRead)
{
  const std::string dir = fixtures::freshTestFolder("slicer-export-refusals").string();
  RegistrationRecord record = timedRecord();
  SlicerSceneOptions options;
  options.transformExtension = ".json";
  EXPECT_EQ(errorMessageOf([&] { writeSlicerScene(record, dir, options); }),
    "'.json' is not the extension of an ITK transform file (expected .tfm, .txt, .h5, .hdf5 or "
    ".mat)");
  record.result.frames.clear();
  EXPECT_EQ(errorMessageOf([&] { writeSlicerScene(record, dir, SlicerSceneOptions()); }),
    "the result has no frames: there is no camera pose to export");
}

TEST(SlicerSceneExport, ReplacesAnEarlierExportButNeverAnotherFolder)
{
  const std::string result = fixtures::freshTestFolder("slicer-export-result").string();
  writeRegistrationRecord(timedRecord(), result);
  const std::string out = fixtures::freshTestFolder("slicer-export-out").string() + "/scene";
  exportResultForSlicer(result, out, false, SlicerSceneOptions());
  EXPECT_TRUE(std::filesystem::exists(out + "/vimlop-export.json"));
  EXPECT_EQ(
    errorMessageOf([&] { exportResultForSlicer(result, out, false, SlicerSceneOptions()); }),
    "'" + out + "': exists; choose another --out or add --force to replace it");
  exportResultForSlicer(result, out, true, SlicerSceneOptions());

  const std::string users = fixtures::freshTestFolder("slicer-export-users").string();
  writeFileAtomically(users + "/notes.txt", "mine\n");
  EXPECT_EQ(
    errorMessageOf([&] { exportResultForSlicer(result, users, true, SlicerSceneOptions()); }),
    "'" + users +
      "': exists and is not a VIMLOP result folder (no result.json, registered-poses.json "
      "or vimlop-export.json); refusing to replace it");
  EXPECT_EQ(readWholeFile(users + "/notes.txt"), "mine\n");

  EXPECT_EQ(
    errorMessageOf([&] { exportResultForSlicer(result, result, true, SlicerSceneOptions()); }),
    "'" + result +
      "': is a registration result folder; an export never replaces one (choose "
      "another --out)");
  EXPECT_NO_THROW(readRegistrationRecord(result));
}
