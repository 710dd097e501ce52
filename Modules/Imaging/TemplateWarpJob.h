#ifndef vimlop_TemplateWarpJob_h
#define vimlop_TemplateWarpJob_h

#include <vimlop/Imaging/ProgressCallback.h>
#include <vimlop/Imaging/TemplateRegistration.h>

#include "VIMLOPImagingModule.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief The inputs of runTemplateWarpJob(), as files (those of `vimlop warp`).
struct TemplateWarpJobOptions
{
  /// Template CT: a file or a DICOM folder (see readCTVolume()). Required.
  std::string templateCTPath;
  /// Patient CT: a file or a DICOM folder. Required.
  std::string patientCTPath;
  /// Meshes in the template CT frame (.vtp, .vtk, .stl, .ply, .obj), each
  /// written warped as <stem>.vtp. None: the template's airway, segmented,
  /// is carried over as airway.vtp.
  std::vector<std::string> templateMeshPaths;
  /// Camera poses in the template CT frame (JSON, see FramePoseIO.h),
  /// written warped as poses.json. Empty: no poses.
  std::string templatePosesPath;
  /// Folder of the outputs, created when missing. Required.
  std::string outputFolder;
  /// The registration's settings (TemplateRegistration's defaults); its
  /// region is replaced by the bounds of the meshes and poses, to which
  /// `registration.marginMm` is added.
  TemplateRegistrationOptions registration;
};

/// @brief What runTemplateWarpJob() did.
struct TemplateWarpJobReport
{
  /// The CTs, as named in the options.
  std::string templateCTPath;
  std::string patientCTPath;
  /// Meshes and camera poses carried into the patient.
  std::size_t meshCount = 0;
  std::size_t poseCount = 0;
  /// Bounds of the mesh points and camera centres, before the margin,
  /// template CT frame: x min, x max, y min, ... (mm).
  std::array<double, 6> regionMm{ 0, 0, 0, 0, 0, 0 };
  /// The registration, its displacement fields included.
  TemplateRegistration registration;
  /// Wall-clock time of the whole job, the last output written excepted (s).
  double totalSeconds = 0.0;
  /// The files written, registration.json excepted: the warped meshes, then
  /// poses.json when there are poses, then the two displacement fields.
  std::vector<std::string> outputPaths;
  /// Every warning, in the order they arose: the template CT's ("template:
  /// ..."), the patient CT's ("patient: ..."), the registration's, and how
  /// many camera centres lie outside the registered region.
  std::vector<std::string> warnings;

  /// @brief The content of registration.json, written in the output folder.
  VIMLOPIMAGING_EXPORT nlohmann::json toJson() const;
};

/// @brief The settings of a template registration as written in
/// registration.json and P4's report: "metric", "syn_levels_mm", ...
VIMLOPIMAGING_EXPORT nlohmann::json settingsJson(const TemplateRegistrationOptions& options);

/**
 * @brief Registers the template CT to the patient CT (TemplateRegistration)
 * over the region of the template meshes and poses plus the margin, and
 * writes into the output folder the meshes and poses carried into the
 * patient, the two displacement fields (template-to-patient.nii.gz,
 * patient-to-template.nii.gz) and registration.json
 * (TemplateWarpJobReport::toJson()).
 *
 * Progress goes to `progress`; each warning, as it arises, to `warning` as
 * well as to the report, so that a caller can show it before a later step fails.
 * @throws vimlop::Error with a one-line message: an unsupported mesh type,
 * two meshes with the same output name (both checked before anything is
 * read), an output folder that cannot be created, an unreadable input, or a
 * failed registration.
 */
VIMLOPIMAGING_EXPORT TemplateWarpJobReport runTemplateWarpJob(const TemplateWarpJobOptions& options,
  const ProgressCallback& progress = ProgressCallback(),
  const std::function<void(const std::string& warning)>& warning =
    std::function<void(const std::string&)>());

} // namespace vimlop

#endif
