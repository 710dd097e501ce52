#ifndef vtkVIMLOPVideoTracking_h
#define vtkVIMLOPVideoTracking_h

#include "VIMLOPPipelineModule.h"

#include <vtkAlgorithm.h>
#include <vtkNew.h>

#include <memory>
#include <string>

class vtkLinearTransform;
class vtkTable;
class vtkTransform;

namespace vimlop
{
class VideoTracking;
} // namespace vimlop

/**
 * @brief The endoscope followed frame by frame after a registration, as a
 * VTK source: `vimlop track` (vimlop::VideoTracking, with its defaults).
 *
 * It starts on the last frame a result folder of `vimlop register`
 * registered and tracks every later frame of FramesPath (a folder, a video
 * file or a tracked sequence) or of a V4L2 camera.
 *
 * Output port 0, vtkTable: one row per tracked frame, in their order:
 * "FrameId", "CameraToCT" (16 components, the camera-to-CT 4 x 4 matrix,
 * row-major; camera x right, y down, z forward; mm), "State" ("tracking",
 * "degraded", "lost": a lost frame's pose is the prediction, not to be
 * shown), "LatencyMs" (the layout of tracked-poses.vtt) and "ContourErrorPx"
 * (see CheckContours).
 *
 * While Update() runs, each frame fires vtkCommand::UpdateEvent once its pose
 * is computed: GetCameraTransform() is then its camera-to-CT pose (held at
 * the last frame not lost), GetLastFrameState() its state and
 * GetLastFrameId() its id, so an observer can follow the scope live.
 * AbortExecute stops after the frame in hand, and the frames tracked are
 * output (and written). Errors (not a result, a flagged result without
 * AllowFlagged, frames of another camera) go through vtkErrorMacro and fail
 * the execution; a frame that cannot be read mid-way ends it with an error,
 * after the frames before it are output.
 */
class VIMLOPPIPELINE_EXPORT vtkVIMLOPVideoTracking : public vtkAlgorithm
{
public:
  static vtkVIMLOPVideoTracking* New();
  vtkTypeMacro(vtkVIMLOPVideoTracking, vtkAlgorithm)
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The result folder of `vimlop register` tracking starts from (required).
  vtkSetStdStringFromCharMacro(ResultFolder);
  vtkGetCharFromStdStringMacro(ResultFolder);
  ///@}

  ///@{
  /// The frames: a folder of pictures, a video file or a tracked sequence,
  /// or, when CameraIndex is 0 or more, the camera /dev/video<CameraIndex>
  /// (default -1: FramesPath).
  vtkSetStdStringFromCharMacro(FramesPath);
  vtkGetCharFromStdStringMacro(FramesPath);
  vtkSetClampMacro(CameraIndex, int, -1, 1000);
  vtkGetMacro(CameraIndex, int);
  ///@}

  ///@{
  /// The intrinsics file given to `register` (its lens undistorts the
  /// frames); empty (default): the frames are used as they are.
  vtkSetStdStringFromCharMacro(IntrinsicsFileName);
  vtkGetCharFromStdStringMacro(IntrinsicsFileName);
  ///@}

  ///@{
  /// The electromagnetic tracker's recording of the scope's tip (a CSV
  /// time_s,x_mm,y_mm,z_mm with qw,qx,qy,qz for a 6-DOF sensor, or a
  /// tracked sequence with TrackerTransformName) and the tracker registered
  /// to the CT (3D Slicer's TrackerToRAS transform file), both or neither
  /// (default): its tip, and a 6-DOF sensor's rotation, at each frame's
  /// time is the tracker's prior (vimlop::EndoscopeTracker::track()). Frame id i is at
  /// TrackerTimeOffset
  /// + (i - the first id) / FramesPerSecond on the tracker's clock.
  vtkSetStdStringFromCharMacro(TrackerFileName);
  vtkGetCharFromStdStringMacro(TrackerFileName);
  vtkSetStdStringFromCharMacro(TrackerTransformName);
  vtkGetCharFromStdStringMacro(TrackerTransformName);
  vtkSetStdStringFromCharMacro(TrackerToCTFileName);
  vtkGetCharFromStdStringMacro(TrackerToCTFileName);
  vtkSetMacro(TrackerTimeOffset, double);
  vtkGetMacro(TrackerTimeOffset, double);
  /// The frames' rate (default 30): the tracked video's, and the frame times.
  vtkSetClampMacro(FramesPerSecond, double, 0.01, 10000.0);
  vtkGetMacro(FramesPerSecond, double);
  ///@}

  ///@{
  /// Where tracked-poses.json and .vtt, tracking.json and tracked-video.avi
  /// are written; empty (default): nothing is written.
  vtkSetStdStringFromCharMacro(OutputFolder);
  vtkGetCharFromStdStringMacro(OutputFolder);
  /// Write tracked-video.avi in OutputFolder (default on).
  vtkSetMacro(WriteVideo, bool);
  vtkGetMacro(WriteVideo, bool);
  vtkBooleanMacro(WriteVideo, bool);
  ///@}

  ///@{
  /// Index of the first frame to track; -1 (default): the one after the
  /// registered frame of the same name, else 0.
  vtkSetClampMacro(FirstFrameIndex, int, -1, VTK_INT_MAX);
  vtkGetMacro(FirstFrameIndex, int);
  /// Check each tracked pose against the CT (default on): the frame's
  /// occluding contours matched to the model's at the pose; the median
  /// error, px, is the table's "ContourErrorPx" (NaN when not checked).
  vtkSetMacro(CheckContours, bool);
  vtkGetMacro(CheckContours, bool);
  vtkBooleanMacro(CheckContours, bool);
  /// With CheckContours: correct the tracker with the contours of its last
  /// frames against the CT (vimlop::ContourWindowRefinement; default on).
  vtkSetMacro(RefineAgainstCT, bool);
  vtkGetMacro(RefineAgainstCT, bool);
  vtkBooleanMacro(RefineAgainstCT, bool);
  /// With CheckContours: search for the pose against the CT when the
  /// tracker lost its anchor to it (frames lost, or followed from features
  /// cast from a prediction) and their contours disagree with the model
  /// (vimlop::relocaliseAgainstCT; default on).
  vtkSetMacro(Relocalise, bool);
  vtkGetMacro(Relocalise, bool);
  vtkBooleanMacro(Relocalise, bool);
  /// Track from a result the registration flagged as a failure (default
  /// off: refused, every tracked pose would carry its error).
  vtkSetMacro(AllowFlagged, bool);
  vtkGetMacro(AllowFlagged, bool);
  vtkBooleanMacro(AllowFlagged, bool);
  ///@}

  ///@{
  /// The tracker's main settings (vimlop::EndoscopeTrackerOptions, same
  /// defaults as `vimlop track`): features tracked at most (300), frames
  /// wider than MaxTrackingWidthPx tracked halved (480 px), a feature agrees
  /// with a pose within InlierThresholdPx (2 px).
  vtkSetClampMacro(MaxFeatures, int, 10, 100000);
  vtkGetMacro(MaxFeatures, int);
  vtkSetClampMacro(MaxTrackingWidthPx, int, 64, 100000);
  vtkGetMacro(MaxTrackingWidthPx, int);
  vtkSetClampMacro(InlierThresholdPx, double, 0.01, 100.0);
  vtkGetMacro(InlierThresholdPx, double);
  /// With an electromagnetic tracker: its error is learned from the frames
  /// tracked against the CT over about TrackerOffsetFrames frames (90; 0:
  /// taken as it reads), and a pose not anchored to the CT is moved
  /// TrackerPull of the way to the corrected tracker's in each frame (0.1).
  vtkSetClampMacro(TrackerOffsetFrames, int, 0, 100000);
  vtkGetMacro(TrackerOffsetFrames, int);
  vtkSetClampMacro(TrackerPull, double, 0.0, 1.0);
  vtkGetMacro(TrackerPull, double);
  /// Its lag behind the frames' times is measured from the video's motion
  /// (its frames not lost), up to TrackerMaxLagS either way (0.2; 0: read
  /// at the frames' times), and its readings taken that much later.
  vtkSetClampMacro(TrackerMaxLagS, double, 0.0, 2.0);
  vtkGetMacro(TrackerMaxLagS, double);
  ///@}

  ///@{
  /// The outputs and the outcome of the last execution.
  vtkTable* GetTrackedPoses();
  /// The last tracked frame's camera-to-CT pose (held at the last frame not
  /// lost); live during Update(), updated in place.
  vtkLinearTransform* GetCameraTransform();
  /// "tracking", "degraded" or "lost"; empty before the first frame.
  std::string GetLastFrameState() const;
  int GetLastFrameId() const;
  int GetNumberOfTrackingFrames() const;
  int GetNumberOfDegradedFrames() const;
  int GetNumberOfLostFrames() const;
  double GetMedianLatencyMs() const;
  /// The error that ended the last run early, after its first frames; empty otherwise.
  std::string GetStoppedBy() const;
  ///@}

  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs) override;

protected:
  vtkVIMLOPVideoTracking();
  ~vtkVIMLOPVideoTracking() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs);

private:
  vtkVIMLOPVideoTracking(const vtkVIMLOPVideoTracking&) = delete;
  void operator=(const vtkVIMLOPVideoTracking&) = delete;

  std::string ResultFolder;
  std::string FramesPath;
  int CameraIndex = -1;
  std::string IntrinsicsFileName;
  std::string OutputFolder;
  std::string TrackerFileName;
  std::string TrackerTransformName;
  std::string TrackerToCTFileName;
  double TrackerTimeOffset = 0.0;
  double FramesPerSecond;
  bool WriteVideo = true;
  int FirstFrameIndex = -1;
  bool AllowFlagged = false;
  bool CheckContours = true;
  bool RefineAgainstCT = true;
  bool Relocalise = true;
  int MaxFeatures;
  int MaxTrackingWidthPx;
  double InlierThresholdPx;
  int TrackerOffsetFrames;
  double TrackerPull;
  double TrackerMaxLagS;
  std::string LastFrameState;
  int LastFrameId = -1;
  std::unique_ptr<vimlop::VideoTracking> Tracking;
  vtkNew<vtkTransform> CameraTransform;
};

#endif
