#include <vimlop/Pipeline/vtkVIMLOPVideoTracking.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Pipeline/VideoTracking.h>
#include <vimlop/Registration/CameraPoseTable.h>

#include <vtkCommand.h>
#include <vtkDemandDrivenPipeline.h>
#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkTable.h>
#include <vtkTransform.h>

#include <exception>
#include <vector>

vtkStandardNewMacro(vtkVIMLOPVideoTracking);

vtkVIMLOPVideoTracking::vtkVIMLOPVideoTracking()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(1);
  // The defaults are the tracker's own, as `vimlop track` has them.
  const vimlop::EndoscopeTrackerOptions defaults;
  this->MaxFeatures = defaults.maxFeatures;
  this->MaxTrackingWidthPx = defaults.maxTrackingWidthPx;
  this->InlierThresholdPx = defaults.inlierThresholdPx;
  this->TrackerOffsetFrames = defaults.trackerOffsetFrames;
  this->TrackerPull = defaults.trackerPull;
  this->TrackerMaxLagS = vimlop::TrackerLagOptions().maxLagS;
  this->FramesPerSecond = vimlop::VideoTrackingOptions().videoFps;
}

vtkVIMLOPVideoTracking::~vtkVIMLOPVideoTracking() = default;

int vtkVIMLOPVideoTracking::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
  return 1;
}

vtkTypeBool vtkVIMLOPVideoTracking::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(request, inputs, outputs);
  }
  return this->Superclass::ProcessRequest(request, inputs, outputs);
}

vtkTable* vtkVIMLOPVideoTracking::GetTrackedPoses()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(0));
}

vtkLinearTransform* vtkVIMLOPVideoTracking::GetCameraTransform()
{
  return this->CameraTransform;
}

std::string vtkVIMLOPVideoTracking::GetLastFrameState() const
{
  return this->LastFrameState;
}

int vtkVIMLOPVideoTracking::GetLastFrameId() const
{
  return this->LastFrameId;
}

int vtkVIMLOPVideoTracking::GetNumberOfTrackingFrames() const
{
  return this->Tracking ? this->Tracking->count(vimlop::TrackingState::Tracking) : 0;
}

int vtkVIMLOPVideoTracking::GetNumberOfDegradedFrames() const
{
  return this->Tracking ? this->Tracking->count(vimlop::TrackingState::Degraded) : 0;
}

int vtkVIMLOPVideoTracking::GetNumberOfLostFrames() const
{
  return this->Tracking ? this->Tracking->count(vimlop::TrackingState::Lost) : 0;
}

double vtkVIMLOPVideoTracking::GetMedianLatencyMs() const
{
  return this->Tracking ? this->Tracking->latencyMs().median : 0.0;
}

std::string vtkVIMLOPVideoTracking::GetStoppedBy() const
{
  return this->Tracking ? this->Tracking->stoppedBy() : std::string();
}

int vtkVIMLOPVideoTracking::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputs)
{
  this->Tracking.reset();
  this->LastFrameState.clear();
  this->LastFrameId = -1;
  this->CameraTransform->Identity();
  vtkTable::GetData(outputs, 0)->Initialize();
  vimlop::VideoTrackingOptions options;
  options.tracker.maxFeatures = this->MaxFeatures;
  options.tracker.maxTrackingWidthPx = this->MaxTrackingWidthPx;
  options.tracker.inlierThresholdPx = this->InlierThresholdPx;
  options.tracker.trackerOffsetFrames = this->TrackerOffsetFrames;
  options.tracker.trackerPull = this->TrackerPull;
  options.trackerLag.maxLagS = this->TrackerMaxLagS;
  options.firstFrameIndex = this->FirstFrameIndex;
  options.allowFlagged = this->AllowFlagged;
  options.writeVideo = this->WriteVideo;
  options.checkContours = this->CheckContours;
  options.refineAgainstCT = this->RefineAgainstCT;
  options.relocalise = this->Relocalise;
  options.videoFps = this->FramesPerSecond;
  auto tracking = std::make_unique<vimlop::VideoTracking>(options);
  tracking->setStopRequest([this] { return this->GetAbortExecute() != 0; });
  tracking->setFrameHandler(
    [this](const vimlop::TrackedVideoFrame& f)
    {
      this->LastFrameState = vimlop::toString(f.tracked.state);
      this->LastFrameId = f.frameId;
      if (f.tracked.state != vimlop::TrackingState::Lost)
      {
        this->CameraTransform->SetMatrix(
          Eigen::Matrix<double, 4, 4, Eigen::RowMajor>(f.tracked.cameraToCT.matrix()).data());
      }
      this->InvokeEvent(vtkCommand::UpdateEvent);
    });
  try
  {
    if (this->ResultFolder.empty() || (this->FramesPath.empty() && this->CameraIndex < 0))
    {
      throw vimlop::Error("set ResultFolder, and FramesPath or CameraIndex");
    }
    vimlop::VideoTrackingInputs inputs;
    inputs.resultFolder = this->ResultFolder;
    inputs.framesPath = this->CameraIndex >= 0 ? std::string() : this->FramesPath;
    inputs.cameraIndex = this->CameraIndex;
    inputs.intrinsicsPath = this->IntrinsicsFileName;
    inputs.outputFolder = this->OutputFolder;
    inputs.trackerPath = this->TrackerFileName;
    inputs.trackerTransform = this->TrackerTransformName;
    inputs.trackerToCTPath = this->TrackerToCTFileName;
    inputs.timeOffsetS = this->TrackerTimeOffset;
    tracking->open(inputs);
    tracking->run();
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  std::vector<vimlop::FramePose> poses;
  std::vector<std::string> states;
  std::vector<double> latencyMs;
  for (const vimlop::TrackedVideoFrame& f : tracking->frames())
  {
    poses.push_back({ f.frameId, f.tracked.cameraToCT });
    states.push_back(vimlop::toString(f.tracked.state));
    latencyMs.push_back(f.latencyMs);
  }
  vtkSmartPointer<vtkTable> table = vimlop::makeTrackedPoseTable(poses, states, latencyMs);
  vtkNew<vtkDoubleArray> contourError;
  contourError->SetName("ContourErrorPx");
  for (const vimlop::TrackedVideoFrame& f : tracking->frames())
  {
    contourError->InsertNextValue(f.contourErrorPx);
  }
  table->AddColumn(contourError);
  vtkTable::GetData(outputs, 0)->ShallowCopy(table);
  this->Tracking = std::move(tracking);
  if (!this->Tracking->stoppedBy().empty())
  {
    vtkErrorMacro(<< "tracking stopped after " << this->Tracking->frames().size()
                  << " frames: " << this->Tracking->stoppedBy());
    return 0;
  }
  return 1;
}

void vtkVIMLOPVideoTracking::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ResultFolder: " << this->ResultFolder << "\n";
  os << indent << "FramesPath: " << this->FramesPath << "\n";
  os << indent << "CameraIndex: " << this->CameraIndex << "\n";
  os << indent << "IntrinsicsFileName: " << this->IntrinsicsFileName << "\n";
  os << indent << "TrackerFileName: " << this->TrackerFileName << "\n";
  os << indent << "TrackerTransformName: " << this->TrackerTransformName << "\n";
  os << indent << "TrackerToCTFileName: " << this->TrackerToCTFileName << "\n";
  os << indent << "TrackerTimeOffset: " << this->TrackerTimeOffset << "\n";
  os << indent << "FramesPerSecond: " << this->FramesPerSecond << "\n";
  os << indent << "OutputFolder: " << this->OutputFolder << "\n";
  os << indent << "WriteVideo: " << (this->WriteVideo ? "On" : "Off") << "\n";
  os << indent << "FirstFrameIndex: " << this->FirstFrameIndex << "\n";
  os << indent << "CheckContours: " << (this->CheckContours ? "On" : "Off") << "\n";
  os << indent << "RefineAgainstCT: " << (this->RefineAgainstCT ? "On" : "Off") << "\n";
  os << indent << "Relocalise: " << (this->Relocalise ? "On" : "Off") << "\n";
  os << indent << "AllowFlagged: " << (this->AllowFlagged ? "On" : "Off") << "\n";
  os << indent << "MaxFeatures: " << this->MaxFeatures << "\n";
  os << indent << "MaxTrackingWidthPx: " << this->MaxTrackingWidthPx << "\n";
  os << indent << "InlierThresholdPx: " << this->InlierThresholdPx << "\n";
  os << indent << "TrackerOffsetFrames: " << this->TrackerOffsetFrames << "\n";
  os << indent << "TrackerPull: " << this->TrackerPull << "\n";
  os << indent << "TrackerMaxLagS: " << this->TrackerMaxLagS << "\n";
  if (this->Tracking)
  {
    os << indent << "Result: " << this->Tracking->frames().size()
       << " frames: " << this->GetNumberOfTrackingFrames() << " tracking, "
       << this->GetNumberOfDegradedFrames() << " degraded, " << this->GetNumberOfLostFrames()
       << " lost\n";
  }
}
