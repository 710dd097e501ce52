#include <vimlop/Pipeline/vtkVIMLOPVideoRegistration.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Pipeline/RegistrationOutputs.h>
#include <vimlop/Pipeline/VideoRegistrationPipeline.h>
#include <vimlop/Registration/RegistrationOutputConversion.h>

#include <vtkDemandDrivenPipeline.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkTable.h>
#include <vtkTransform.h>

#include <exception>

vtkStandardNewMacro(vtkVIMLOPVideoRegistration);

vtkVIMLOPVideoRegistration::vtkVIMLOPVideoRegistration()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
}

vtkVIMLOPVideoRegistration::~vtkVIMLOPVideoRegistration() = default;

int vtkVIMLOPVideoRegistration::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkTable" : "vtkPolyData");
  return 1;
}

vtkTypeBool vtkVIMLOPVideoRegistration::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(request, inputs, outputs);
  }
  return this->Superclass::ProcessRequest(request, inputs, outputs);
}

vimlop::VideoRegistrationOptions& vtkVIMLOPVideoRegistration::GetOptions()
{
  this->Modified();
  return this->Options;
}

std::string vtkVIMLOPVideoRegistration::GetOptionsAsJSON() const
{
  return vimlop::registrationOptionsJson(this->Options).dump(2);
}

vtkTable* vtkVIMLOPVideoRegistration::GetCameraPoses()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(0));
}

vtkPolyData* vtkVIMLOPVideoRegistration::GetRegisteredPoints()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

vtkLinearTransform* vtkVIMLOPVideoRegistration::GetTransform()
{
  return this->Transform;
}

bool vtkVIMLOPVideoRegistration::GetFlaggedAsFailure() const
{
  return this->Pipeline && this->Pipeline->flaggedAsFailure();
}

double vtkVIMLOPVideoRegistration::GetContourErrorPx() const
{
  return this->Pipeline ? this->Pipeline->result().contourErrorPx : 0.0;
}

double vtkVIMLOPVideoRegistration::GetResidualErrorMm() const
{
  return this->Pipeline ? this->Pipeline->result().residualErrorMm : 0.0;
}

int vtkVIMLOPVideoRegistration::GetNumberOfCandidates() const
{
  return this->Pipeline ? static_cast<int>(this->Pipeline->outcome().candidates.size()) : 0;
}

int vtkVIMLOPVideoRegistration::GetNumberOfRegisteredFrames() const
{
  return this->Pipeline ? static_cast<int>(this->Pipeline->result().frames.size()) : 0;
}

int vtkVIMLOPVideoRegistration::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputs)
{
  this->Pipeline.reset();
  auto pipeline = std::make_unique<vimlop::VideoRegistrationPipeline>(this->Options);
  pipeline->setWarningHandler([this](const std::string& text) { vtkWarningMacro(<< text); });
  // The stages in their order, with a share of the progress each.
  const char* stages[] = { "frames", "model", "contours", "sfm", "registration" };
  pipeline->setProgress(
    [this, &stages](const std::string& stage, double fraction)
    {
      for (int i = 0; i < 5; ++i)
      {
        if (stage.rfind(stages[i], 0) == 0)
        {
          this->UpdateProgress((i + fraction) / 5.0);
        }
      }
      return !this->GetAbortExecute();
    });
  try
  {
    if (this->FramesPath.empty() || this->IntrinsicsFileName.empty())
    {
      throw vimlop::Error("set FramesPath and IntrinsicsFileName");
    }
    vimlop::VideoRegistrationInputs inputs;
    inputs.meshPath = this->MeshFileName;
    inputs.ctPath = this->CTFileName;
    inputs.framesPath = this->FramesPath;
    inputs.maxFrames = this->MaxFrames;
    inputs.intrinsicsPath = this->IntrinsicsFileName;
    inputs.colmapFolder = this->ColmapFolder;
    inputs.sfmFile = this->SfmFileName;
    inputs.contoursFile = this->ContoursFileName;
    inputs.trackerPath = this->TrackerFileName;
    inputs.initialScale = this->InitialScale;
    inputs.trackerTransform = this->TrackerTransformName;
    inputs.trackerToCTPath = this->TrackerToCTFileName;
    inputs.framesPerSecond = this->FramesPerSecond;
    inputs.timeOffsetS = this->TimeOffset;
    inputs.startMode =
      this->StartFromManualPose ? vimlop::StartMode::Manual : vimlop::StartMode::Canonical;
    inputs.startPosesPath = this->StartPosesFileName;
    pipeline->run(inputs);
  }
  catch (const vimlop::PipelineCancelled&)
  {
    vtkErrorMacro(<< "cancelled (AbortExecute)");
    return 0;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  const vimlop::RegistrationResult& result = pipeline->result();
  this->Transform->SetMatrix(
    Eigen::Matrix<double, 4, 4, Eigen::RowMajor>(result.sfmToCT.matrix()).data());
  vtkTable::GetData(outputs, 0)->ShallowCopy(vimlop::makeFrameResultTable(result));
  vtkPolyData::GetData(outputs, 1)
    ->ShallowCopy(vimlop::makeRegisteredPointPolyData(pipeline->data(), result));
  this->Pipeline = std::move(pipeline);
  return 1;
}

void vtkVIMLOPVideoRegistration::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MeshFileName: " << this->MeshFileName << "\n";
  os << indent << "CTFileName: " << this->CTFileName << "\n";
  os << indent << "FramesPath: " << this->FramesPath << "\n";
  os << indent << "IntrinsicsFileName: " << this->IntrinsicsFileName << "\n";
  os << indent << "TrackerFileName: " << this->TrackerFileName << "\n";
  os << indent << "InitialScale: " << this->InitialScale << "\n";
  os << indent << "TrackerTransformName: " << this->TrackerTransformName << "\n";
  os << indent << "TrackerToCTFileName: " << this->TrackerToCTFileName << "\n";
  os << indent << "FramesPerSecond: " << this->FramesPerSecond << "\n";
  os << indent << "TimeOffset: " << this->TimeOffset << "\n";
  os << indent << "ColmapFolder: " << this->ColmapFolder << "\n";
  os << indent << "SfmFileName: " << this->SfmFileName << "\n";
  os << indent << "ContoursFileName: " << this->ContoursFileName << "\n";
  os << indent << "StartPosesFileName: " << this->StartPosesFileName << "\n";
  os << indent << "StartFromManualPose: " << (this->StartFromManualPose ? "On" : "Off") << "\n";
  os << indent << "MaxFrames: " << this->MaxFrames << "\n";
  VIMLOP_REGISTRATION_VALUES(vtkVIMLOPPrintValueOption)
  VIMLOP_REGISTRATION_SWITCHES(vtkVIMLOPPrintSwitchOption)
  VIMLOP_VIDEO_REGISTRATION_VALUES(vtkVIMLOPPrintValueOption)
  if (this->Pipeline)
  {
    os << indent << "Result: " << this->GetNumberOfRegisteredFrames() << " frames, contour error "
       << this->GetContourErrorPx() << " px"
       << (this->GetFlaggedAsFailure() ? ", FLAGGED AS A FAILURE" : "") << "\n";
  }
}
