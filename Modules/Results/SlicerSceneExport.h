#ifndef vimlop_SlicerSceneExport_h
#define vimlop_SlicerSceneExport_h

#include <vimlop/Results/RegistrationRecord.h>

#include <functional>
#include <string>
#include <vector>

/**
 * @file SlicerSceneExport.h
 * @brief A registration result in the forms 3D Slicer and ITK read: ITK
 * transform files, a Slicer transform sequence of the camera path, and a
 * Slicer scene that holds them with the CT, the airway and the registered
 * points (Documentation/Exchange.md).
 *
 * The export folder:
 *
 * | file | content |
 * |------|---------|
 * | `Scene.mrml` | the Slicer scene: the files below, the camera moving along its path |
 * | `CT.nrrd` | the CT (when one is given), LPS |
 * | `Airway.vtk` | the model registered to, LPS (the header says `SPACE=LPS`) |
 * | `RegisteredPoints.vtk` | the SfM points moved into the CT by the result, LPS |
 * | `CameraPath.vtk` | the optical centres of the frames as a line, LPS |
 * | `Endoscope.vtk` | a small cone along the camera's optical axis, camera frame |
 * | `CameraToCT.seq.mha` | the camera-to-CT pose of every frame at its time: Slicer's linear
 * transform sequence (TransformSequenceFile.h) | | `Transforms/SfMToCT.tfm` | the SfM-to-CT
 * similarity, ITK resampling form (see below) | | `Transforms/CameraToCT-<id>.tfm` | each frame's
 * camera pose, ITK resampling form | | `vimlop-export.json` | what was exported from where, with
 * the conventions of every file |
 *
 * ITK transform files hold the resampling transform, from the fixed space to
 * the moving space; a transform named "AToB" (points of A to points of B) is
 * therefore stored as its inverse, B to A, so that ITK, ANTs and 3D Slicer
 * (which shows a file's transform as the inverse of what it holds, from
 * child to parent) all read "AToB" the same way. Both spaces are LPS.
 */

namespace vimlop
{

/// @brief What writeSlicerScene() adds to the result's own content.
struct SlicerSceneOptions
{
  /// The CT to put in the scene as CT.nrrd (any readCTVolume() input); empty:
  /// the CT the result names (its "ct" input) when `ctFromResult` and that
  /// file is still there, else no CT.
  std::string ctPath;
  bool ctFromResult = false;
  /// The format of the ITK transform files: ".tfm" (text), ".h5" (HDF5) or ".mat".
  std::string transformExtension = ".tfm";
  /// Called with each step, for people ("writing CT.nrrd"); may be empty.
  std::function<void(const std::string&)> onProgress;
};

/// @brief What writeSlicerScene() wrote.
struct SlicerSceneFiles
{
  /// Every file written, relative to the export folder, the scene first.
  std::vector<std::string> files;
  /// The number of frame poses written (files and sequence items).
  int frames = 0;
  bool withCT = false;
};

/**
 * @brief Writes the export folder above into `folder` (which must exist and
 * be empty, see exportResultForSlicer()).
 * @throws vimlop::Error naming the file that could not be read or written, a
 * transform extension that is not one of ITK's, or a result without frames.
 */
SlicerSceneFiles writeSlicerScene(
  const RegistrationRecord& record, const std::string& folder, const SlicerSceneOptions& options);

/**
 * @brief Reads the result folder `resultFolder` and writes its export into
 * `exportFolder` as one step (ResultFolderTransaction): the folder is the old
 * one or the complete new one. An existing export folder is replaced only
 * when `replace` is true and it is empty or an earlier export
 * (vimlop-export.json).
 * @throws vimlop::Error as readRegistrationRecord() and writeSlicerScene() do.
 */
SlicerSceneFiles exportResultForSlicer(const std::string& resultFolder,
  const std::string& exportFolder, bool replace, const SlicerSceneOptions& options);

} // namespace vimlop

#endif
