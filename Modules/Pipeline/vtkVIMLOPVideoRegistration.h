#ifndef vtkVIMLOPVideoRegistration_h
#define vtkVIMLOPVideoRegistration_h

#include "VIMLOPPipelineModule.h"
#include <vimlop/Core/RegistrationOptionTable.h>
#include <vimlop/Pipeline/VideoRegistrationOptionTable.h>
#include <vimlop/Pipeline/VideoRegistrationOptions.h>
#include <vimlop/Registration/VTKOptionMacros.h>

#include <vtkAlgorithm.h>
#include <vtkNew.h>

#include <memory>
#include <string>

class vtkLinearTransform;
class vtkPolyData;
class vtkTable;
class vtkTransform;

namespace vimlop
{
class VideoRegistrationPipeline;
} // namespace vimlop

/**
 * @brief The whole main job as a VTK source: a CT (or its airway mesh) and a
 * video sequence with its intrinsics and tracker recording in; the camera
 * pose of every registered frame in CT, the SfM-to-CT transform and the
 * failure flag out. It runs vimlop::VideoRegistrationPipeline with the
 * defaults `vimlop register` uses (vimlop::VideoRegistrationOptions):
 * contours, SfM, the tracker's scale (V14), the multi-start from canonical
 * poses along the airway (V13 b) or from one frame's given pose (V13 a), and
 * the contour-error failure flag.
 *
 * Outputs:
 * - port 0, vtkTable: one row per registered frame: "FrameId", "CameraToCT"
 *   (16 components, the camera-to-CT 4 x 4 matrix, row-major; camera x
 *   right, y down, z forward; mm), its contour error and inlier counts (the
 *   layout of vtkVIMLOPRegistration's port 1);
 * - port 1, vtkPolyData: the SfM points in the CT frame with inlier flags.
 * GetTransform() is the estimated similarity T (SfM to CT), updated in place
 * at every execution. The inputs are files, named by the setters below; the
 * filter re-executes when a setter changes a value.
 *
 * Errors (unreadable files, too little SfM, no start inside the airway) are
 * reported through vtkErrorMacro and fail the execution; progress events
 * follow the pipeline's stages, and AbortExecute cancels it.
 */
class VIMLOPPIPELINE_EXPORT vtkVIMLOPVideoRegistration : public vtkAlgorithm
{
public:
  static vtkVIMLOPVideoRegistration* New();
  vtkTypeMacro(vtkVIMLOPVideoRegistration, vtkAlgorithm)
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The model: an airway mesh (CT frame, normals into the air) or, when
  /// MeshFileName is empty, a CT volume whose airway is segmented.
  vtkSetStdStringFromCharMacro(MeshFileName);
  vtkGetCharFromStdStringMacro(MeshFileName);
  vtkSetStdStringFromCharMacro(CTFileName);
  vtkGetCharFromStdStringMacro(CTFileName);
  ///@}

  ///@{
  /// The video: a folder of frames or a video file, and its intrinsics
  /// (OpenCV YAML/JSON/XML; distortion is removed first).
  vtkSetStdStringFromCharMacro(FramesPath);
  vtkGetCharFromStdStringMacro(FramesPath);
  vtkSetStdStringFromCharMacro(IntrinsicsFileName);
  vtkGetCharFromStdStringMacro(IntrinsicsFileName);
  ///@}

  ///@{
  /// V14: the tracker recording (CSV: time_s,x_mm,y_mm,z_mm) that gives the
  /// initial scale, or the initial scale itself (mm per SfM unit, wins when
  /// positive). One of the two is required.
  vtkSetStdStringFromCharMacro(TrackerFileName);
  vtkGetCharFromStdStringMacro(TrackerFileName);
  vtkSetClampMacro(InitialScale, double, 0.0, 1e12);
  vtkGetMacro(InitialScale, double);
  ///@}

  ///@{
  /// The transform of a tracked sequence that carries the scope (e.g.
  /// "ProbeToTracker"), read from TrackerFileName or, when that is empty,
  /// from FramesPath; empty (the default): the tracker is a CSV.
  vtkSetStdStringFromCharMacro(TrackerTransformName);
  vtkGetCharFromStdStringMacro(TrackerTransformName);
  /// The tracker registered to the patient, as 3D Slicer saves its
  /// TrackerToRAS transform (an ITK transform file): the tracked camera (a
  /// 6-DOF sensor: a tracked sequence's transform or a CSV with
  /// qw,qx,qy,qz) turns the canonical starts, a rotation prior (empty, the
  /// default: none).
  vtkSetStdStringFromCharMacro(TrackerToCTFileName);
  vtkGetCharFromStdStringMacro(TrackerToCTFileName);
  /// Frame times on the tracker's clock: the frames' own timestamps (a
  /// tracked sequence) plus TimeOffset, or their video's rate; a positive
  /// FramesPerSecond overrides either (frame f at TimeOffset + f /
  /// FramesPerSecond, s); a folder's frames are 30 fps apart unless it is
  /// set (defaults 0 and 0).
  vtkSetClampMacro(FramesPerSecond, double, 0.0, 1e6);
  vtkGetMacro(FramesPerSecond, double);
  vtkSetMacro(TimeOffset, double);
  vtkGetMacro(TimeOffset, double);
  ///@}

  ///@{
  /// Structure from motion: empty for the built-in one (default), else a
  /// COLMAP sparse model folder (text or binary).
  vtkSetStdStringFromCharMacro(ColmapFolder);
  vtkGetCharFromStdStringMacro(ColmapFolder);
  ///@}

  ///@{
  /// Earlier stages' outputs to reuse (default: none, computed here): a
  /// `vimlop sfm` file instead of the structure from motion, a `vimlop
  /// contours` file instead of the contour detection (frames matched by name).
  vtkSetStdStringFromCharMacro(SfmFileName);
  vtkGetCharFromStdStringMacro(SfmFileName);
  vtkSetStdStringFromCharMacro(ContoursFileName);
  vtkGetCharFromStdStringMacro(ContoursFileName);
  ///@}

  ///@{
  /// V13: the start. Empty (default): canonical poses generated along the
  /// airway. A pose file (FramePose JSON) with StartFromManualPose off:
  /// canonical poses from it (e.g. template poses warped to the patient);
  /// with StartFromManualPose on: its first pose is the camera-to-CT pose of
  /// that frame, one start.
  vtkSetStdStringFromCharMacro(StartPosesFileName);
  vtkGetCharFromStdStringMacro(StartPosesFileName);
  vtkSetMacro(StartFromManualPose, bool);
  vtkGetMacro(StartFromManualPose, bool);
  vtkBooleanMacro(StartFromManualPose, bool);
  ///@}

  ///@{
  /// Read at most this many frames (default 1000).
  vtkSetClampMacro(MaxFrames, int, 2, 100000);
  vtkGetMacro(MaxFrames, int);
  ///@}

  ///@{
  /**
   * Every setting of vimlop::VideoRegistrationOptions, generated from
   * RegistrationOptionTable.h and VideoRegistrationOptionTable.h (meaning,
   * unit, range; the defaults are `vimlop register`'s): numbers as
   * Set<Name>/Get<Name>, clamped into [Get<Name>MinValue(),
   * Get<Name>MaxValue()], e.g. SetNumberOfThreads, SetFailureThresholdPx,
   * SetCanonicalSpacingMm, SetContourKappa, SetMaxIterations; switches as
   * Set<Name>, <Name>On and <Name>Off, e.g. AnatomicalConstraintOff().
   */
#define vtkVIMLOPVideoRegistrationValue(Name, Type, member, key, flag, min, max, help)             \
  vtkVIMLOPValueOptionMacro(this->Options.registration.member, Name, Type, min, max)
#define vtkVIMLOPVideoRegistrationSwitch(Name, member, key, flag, help)                            \
  vtkVIMLOPSwitchOptionMacro(this->Options.registration.member, Name)
#define vtkVIMLOPVideoRegistrationOwnValue(Name, Type, member, key, flag, min, max, help)          \
  vtkVIMLOPValueOptionMacro(this->Options.member, Name, Type, min, max)
  VIMLOP_REGISTRATION_VALUES(vtkVIMLOPVideoRegistrationValue)
  VIMLOP_REGISTRATION_SWITCHES(vtkVIMLOPVideoRegistrationSwitch)
  VIMLOP_VIDEO_REGISTRATION_VALUES(vtkVIMLOPVideoRegistrationOwnValue)
#undef vtkVIMLOPVideoRegistrationValue
#undef vtkVIMLOPVideoRegistrationSwitch
#undef vtkVIMLOPVideoRegistrationOwnValue
  ///@}

  /// @brief Every setting of the main job (C++: change any of them before Update()).
  vimlop::VideoRegistrationOptions& GetOptions();
  /// @brief The settings as JSON (the layout of `vimlop register --print-options`).
  std::string GetOptionsAsJSON() const;

  ///@{
  /// The outputs (see the class description); valid after Update().
  vtkTable* GetCameraPoses();
  vtkPolyData* GetRegisteredPoints();
  /// T, SfM frame to CT frame (live: updated in place at every execution).
  vtkLinearTransform* GetTransform();
  ///@}

  ///@{
  /// Outcome of the last execution.
  bool GetFlaggedAsFailure() const;
  double GetContourErrorPx() const;
  double GetResidualErrorMm() const;
  int GetNumberOfCandidates() const;
  int GetNumberOfRegisteredFrames() const;
  /// The pipeline of the last execution (its stages' products), or null.
  const vimlop::VideoRegistrationPipeline* GetPipeline() const
  {
    return this->Pipeline.get();
  }
  ///@}

  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs) override;

protected:
  vtkVIMLOPVideoRegistration();
  ~vtkVIMLOPVideoRegistration() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs);

private:
  vtkVIMLOPVideoRegistration(const vtkVIMLOPVideoRegistration&) = delete;
  void operator=(const vtkVIMLOPVideoRegistration&) = delete;

  std::string MeshFileName;
  std::string CTFileName;
  std::string FramesPath;
  std::string IntrinsicsFileName;
  std::string TrackerFileName;
  std::string ColmapFolder;
  std::string SfmFileName;
  std::string ContoursFileName;
  std::string StartPosesFileName;
  bool StartFromManualPose = false;
  double InitialScale = 0.0;
  std::string TrackerTransformName;
  std::string TrackerToCTFileName;
  double FramesPerSecond = 0.0;
  double TimeOffset = 0.0;
  int MaxFrames = 1000;
  vimlop::VideoRegistrationOptions Options;
  std::unique_ptr<vimlop::VideoRegistrationPipeline> Pipeline;
  vtkNew<vtkTransform> Transform;
};

#endif
