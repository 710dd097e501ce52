#include <vimlop/Evaluation/TrialSaving.h>

#include <vimlop/Core/FileError.h>
#include <vimlop/Rendering/PNGImageIO.h>
#include <vimlop/Rendering/SurfaceView.h>
#include <vimlop/Results/RegistrationRecordIO.h>

#include <vtkImageData.h>

#include <filesystem>

namespace vimlop
{

void saveSyntheticTrial(const std::string& folder, const std::string& source,
  const TriangleMesh& mesh, const SyntheticTrial& trial, const RegistrationOptions& options,
  const RegistrationResult& result)
{
  RegistrationRecord record;
  record.source = source;
  record.model = mesh;
  record.data = trial.data;
  record.options = options;
  record.initialSfmToCT = trial.initialSfmToCT;
  record.result = result;
  record.truth =
    RegistrationRecord::GroundTruth{ trial.truthSfmToCT, trial.trueCamerasCT, trial.targetsCT };

  const std::filesystem::path frames = std::filesystem::path(folder) / "frames";
  std::error_code ec;
  std::filesystem::create_directories(frames, ec);
  if (!std::filesystem::is_directory(frames))
  {
    throwFileError(frames.string(), "cannot create the folder");
  }
  for (size_t j = 0; j < trial.data.frames.size(); ++j)
  {
    const VideoFrame& frame = trial.data.frames[j];
    const std::string name = resultFrameImageName(frame.frameId);
    writePNG(renderSurfaceView(mesh, frame.intrinsics, trial.trueCamerasCT[j]),
      (std::filesystem::path(folder) / name).string());
    record.frameImages.push_back(name);
  }
  writeRegistrationRecord(record, folder);
}

} // namespace vimlop
