#include <vimlop/Registration/vtkVIMLOPRegistration.h>

#include <vimlop/Core/CanonicalStarts.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/MethodDescriptor.h>
#include <vimlop/Core/Registration.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Registration/RegistrationInputConversion.h>
#include <vimlop/Registration/RegistrationOutputConversion.h>
#include <vimlop/Rendering/OffscreenRendering.h>
#include <vimlop/Rendering/vtkVIMLOPDepthVisibility.h>

#include <vtkAlgorithmOutput.h>
#include <vtkDemandDrivenPipeline.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkLinearTransform.h>
#include <vtkMatrix4x4.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkTable.h>
#include <vtkTransform.h>
#include <vtkTransformCollection.h>

#include <cmath>
#include <exception>

vtkStandardNewMacro(vtkVIMLOPRegistration);

namespace
{

const char* backendName(vtkVIMLOPRegistration::VisibilityBackend backend)
{
  return backend == vtkVIMLOPRegistration::VisibilityBackend::Embree ? "Embree" : "ZBuffer";
}

} // namespace

vtkVIMLOPRegistration::vtkVIMLOPRegistration()
{
  // Options, MultiStart and Canonical keep Core's defaults: the main job's,
  // which vimlop::VideoRegistrationOptions holds for `vimlop register` and Python.
  this->SetNumberOfInputPorts(4);
  this->SetNumberOfOutputPorts(3);
}

vtkVIMLOPRegistration::~vtkVIMLOPRegistration() = default;

template <typename T>
void vtkVIMLOPRegistration::SetOption(T& field, T value)
{
  if (field != value)
  {
    field = value;
    this->Modified();
  }
}

int vtkVIMLOPRegistration::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(
    vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == FramesPort ? "vtkTable" : "vtkPolyData");
  // Checked in RequestData, which can say what is missing and why.
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkVIMLOPRegistration::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == CameraPosesPort ? "vtkTable" : "vtkPolyData");
  return 1;
}

vtkTypeBool vtkVIMLOPRegistration::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(request, inputs, outputs);
  }
  return this->Superclass::ProcessRequest(request, inputs, outputs);
}

void vtkVIMLOPRegistration::SetModelConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(ModelPort, output);
}

void vtkVIMLOPRegistration::SetModelData(vtkPolyData* surface)
{
  this->SetInputDataObject(ModelPort, surface);
}

void vtkVIMLOPRegistration::SetPointsConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(PointsPort, output);
}

void vtkVIMLOPRegistration::SetPointsData(vtkPolyData* points)
{
  this->SetInputDataObject(PointsPort, points);
}

void vtkVIMLOPRegistration::SetFramesConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(FramesPort, output);
}

void vtkVIMLOPRegistration::SetFramesData(vtkTable* frames)
{
  this->SetInputDataObject(FramesPort, frames);
}

void vtkVIMLOPRegistration::SetContoursConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(ContoursPort, output);
}

void vtkVIMLOPRegistration::SetContoursData(vtkPolyData* contours)
{
  this->SetInputDataObject(ContoursPort, contours);
}

vtkPolyData* vtkVIMLOPRegistration::GetRegisteredPoints()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(RegisteredPointsPort));
}

vtkTable* vtkVIMLOPRegistration::GetCameraPoses()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(CameraPosesPort));
}

vtkPolyData* vtkVIMLOPRegistration::GetCorrespondences()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(CorrespondencesPort));
}

vtkLinearTransform* vtkVIMLOPRegistration::GetTransform()
{
  return this->Transform;
}

void vtkVIMLOPRegistration::SetInitialTransform(vtkLinearTransform* transform)
{
  if (this->InitialTransform != transform)
  {
    this->InitialTransform = transform;
    this->Modified();
  }
}

vtkLinearTransform* vtkVIMLOPRegistration::GetInitialTransform()
{
  return this->InitialTransform;
}

vtkMTimeType vtkVIMLOPRegistration::GetMTime()
{
  vtkMTimeType time = this->Superclass::GetMTime();
  if (this->InitialTransform)
  {
    time = std::max(time, this->InitialTransform->GetMTime());
  }
  if (this->Starts)
  {
    time = std::max(time, this->Starts->GetMTime());
  }
  return time;
}

void vtkVIMLOPRegistration::SetStarts(vtkTransformCollection* starts)
{
  if (this->Starts != starts)
  {
    this->Starts = starts;
    this->Modified();
  }
}

vtkTransformCollection* vtkVIMLOPRegistration::GetStarts()
{
  return this->Starts;
}

void vtkVIMLOPRegistration::SetFailureThresholdPx(double threshold)
{
  this->SetOption(this->MultiStart.failureContourErrorPx, threshold);
}

void vtkVIMLOPRegistration::SetFailureResidualMm(double threshold)
{
  this->SetOption(this->MultiStart.failureResidualErrorMm, threshold);
}

namespace
{

/// A VTK transform as a similarity; `what` names it in the error.
vimlop::SimilarityTransform similarityOf(vtkLinearTransform* transform, const std::string& what)
{
  Eigen::Matrix<double, 4, 4, Eigen::RowMajor> m;
  vtkMatrix4x4* matrix = transform->GetMatrix();
  std::copy(&matrix->Element[0][0], &matrix->Element[0][0] + 16, m.data());
  try
  {
    return vimlop::SimilarityTransform::fromMatrix(m, 1e-6);
  }
  catch (const vimlop::Error& e)
  {
    throw vimlop::Error(what + " is not a similarity: " + e.what());
  }
}

} // namespace

std::vector<vimlop::SimilarityTransform> vtkVIMLOPRegistration::StartsFor(
  const vimlop::RegistrationModel& model) const
{
  std::vector<vimlop::SimilarityTransform> starts;
  if (this->StartFromCanonicalPoses)
  {
    if (!(this->InitialScale > 0.0))
    {
      throw vimlop::Error("canonical starts need InitialScale (mm per SfM unit)");
    }
    return vimlop::canonicalStarts(
      this->Data, this->InitialScale, vimlop::makeCanonicalPoses(model, this->Canonical));
  }
  if (this->Starts && this->Starts->GetNumberOfItems() > 0)
  {
    this->Starts->InitTraversal();
    for (int i = 0; i < this->Starts->GetNumberOfItems(); ++i)
    {
      starts.push_back(similarityOf(this->Starts->GetNextItem(), "start " + std::to_string(i)));
    }
    return starts;
  }
  starts.push_back(this->InitialTransform
      ? similarityOf(this->InitialTransform, "the initial transform")
      : vimlop::SimilarityTransform());
  return starts;
}

void vtkVIMLOPRegistration::SetMethod(vimlop::RegistrationMethod method)
{
  this->SetOption(this->Options.method, method);
}

void vtkVIMLOPRegistration::SetVisibilityBackend(VisibilityBackend backend)
{
  this->SetOption(this->Backend, backend);
}

void vtkVIMLOPRegistration::SetContourPositionCovariancePx2(double uu, double uv, double vv)
{
  Eigen::Matrix2d c;
  c << uu, uv, uv, vv;
  if (c != this->Options.contourMatch.positionCovariancePx2)
  {
    this->Options.contourMatch.positionCovariancePx2 = c;
    this->Modified();
  }
}

void vtkVIMLOPRegistration::GetContourPositionCovariancePx2(double covariance[3]) const
{
  const Eigen::Matrix2d& c = this->Options.contourMatch.positionCovariancePx2;
  covariance[0] = c(0, 0);
  covariance[1] = c(0, 1);
  covariance[2] = c(1, 1);
}

void vtkVIMLOPRegistration::SetMinScale(double scale)
{
  this->SetOption(this->Options.minScale, scale);
}

void vtkVIMLOPRegistration::SetMaxScale(double scale)
{
  this->SetOption(this->Options.maxScale, scale);
}

const vimlop::RegistrationModel& vtkVIMLOPRegistration::ModelFor(vtkPolyData* surface)
{
  if (this->Model && this->ModelSource == surface && this->ModelTime >= surface->GetMTime() &&
    this->ModelBackend == this->Backend)
  {
    return *this->Model;
  }
  this->Model.reset();
  std::string note;
  const vimlop::TriangleMesh mesh = vimlop::toModelMesh(surface, &note);
  if (!note.empty())
  {
    vtkWarningMacro(<< note);
  }
  auto model =
    std::make_unique<vimlop::RegistrationModel>(vimlop::makeEmbreeRegistrationModel(mesh));
  if (this->Backend == VisibilityBackend::ZBuffer)
  {
    vimlop::requireOffscreenRendering("the z-buffer visibility backend");
    this->DepthVisibility = vtkSmartPointer<vtkVIMLOPDepthVisibility>::New();
    this->DepthVisibility->SetMesh(mesh);
    model->setVisibility(this->DepthVisibility->AsContourVisibility());
  }
  this->Model = std::move(model);
  this->ModelSource = surface;
  this->ModelTime = surface->GetMTime();
  this->ModelBackend = this->Backend;
  return *this->Model;
}

int vtkVIMLOPRegistration::RequestData(
  vtkInformation*, vtkInformationVector** inputs, vtkInformationVector* outputs)
{
  vtkPolyData* surface = vtkPolyData::GetData(inputs[ModelPort], 0);
  vtkPolyData* points = vtkPolyData::GetData(inputs[PointsPort], 0);
  vtkTable* frames = vtkTable::GetData(inputs[FramesPort], 0);
  vtkPolyData* contours = vtkPolyData::GetData(inputs[ContoursPort], 0);
  if (!surface)
  {
    vtkErrorMacro(<< "no model surface on input port 0 (SetModelConnection or SetModelData)");
    return 0;
  }
  if (!points)
  {
    vtkErrorMacro(<< "no SfM points on input port 1 (SetPointsConnection or SetPointsData)");
    return 0;
  }
  if (vimlop::describeMethod(this->Options.method).usesContours && (!frames || !contours))
  {
    vtkErrorMacro(<< "V-IMLOP needs the frame table on input port 2 and the video contours on "
                     "input port 3 (IMLP and trimmed ICP register the points alone)");
    return 0;
  }

  try
  {
    this->Data = vimlop::toRegistrationData(points, frames, contours, this->DefaultPointSigmaMm);
    const vimlop::RegistrationModel& model = this->ModelFor(surface);
    const std::vector<vimlop::SimilarityTransform> starts = this->StartsFor(model);
    if (starts.size() == 1 && !this->StartFromCanonicalPoses)
    {
      const double maxIterations = std::max(this->Options.maxIterations, 1);
      auto callback = [this, maxIterations](const vimlop::IterationRecord& record)
      {
        this->UpdateProgress(std::min(1.0, record.iteration / maxIterations));
        this->Current = record;
        this->InvokeEvent(IterationEvent, const_cast<vimlop::IterationRecord*>(&record));
        return !this->GetAbortExecute();
      };
      this->Result =
        vimlop::registerVideo(model, this->Data, starts.front(), this->Options, callback);
      this->Outcome = vimlop::MultiStartResult();
      this->Outcome.candidates.resize(1);
      this->Outcome.candidates[0].initialSfmToCT = starts.front();
      this->Outcome.bestCandidate = 0;
      this->Outcome.best = this->Result;
      this->Outcome.flagFailure(this->MultiStart);
    }
    else
    {
      vimlop::MultiStartOptions multi = this->MultiStart;
      multi.registration = this->Options;
      multi.threads = this->Options.threads;
      // Candidates run in parallel: one progress event per finished candidate.
      this->Outcome = vimlop::registerMultiStart(model, this->Data, starts, multi,
        [this](const char*, int done, int total)
        {
          this->UpdateProgress(static_cast<double>(done) / std::max(total, 1));
          return !this->GetAbortExecute();
        });
      this->Result = this->Outcome.best;
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    this->Result = vimlop::RegistrationResult();
    this->Outcome = vimlop::MultiStartResult();
    return 0;
  }

  this->Transform->SetMatrix(
    Eigen::Matrix<double, 4, 4, Eigen::RowMajor>(this->Result.sfmToCT.matrix()).data());
  vtkPolyData::GetData(outputs, RegisteredPointsPort)
    ->ShallowCopy(vimlop::makeRegisteredPointPolyData(this->Data, this->Result));
  vtkTable::GetData(outputs, CameraPosesPort)
    ->ShallowCopy(vimlop::makeFrameResultTable(this->Result));
  vtkPolyData::GetData(outputs, CorrespondencesPort)
    ->ShallowCopy(vimlop::makeCorrespondencePolyData(this->Result));
  return 1;
}

void vtkVIMLOPRegistration::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vimlop::RegistrationOptions& o = this->Options;
  os << indent << "Method: " << vimlop::toString(o.method) << "\n";
  os << indent << "VisibilityBackend: " << backendName(this->Backend) << "\n";
  os << indent << "DefaultPointSigmaMm: " << this->DefaultPointSigmaMm << "\n";
  const Eigen::Matrix2d& c = o.contourMatch.positionCovariancePx2;
  os << indent << "ContourPositionCovariancePx2: (" << c(0, 0) << ", " << c(0, 1) << ", " << c(1, 1)
     << ")\n";
  os << indent << "MinScale: " << o.minScale << "\n";
  os << indent << "MaxScale: " << o.maxScale << "\n";
  VIMLOP_REGISTRATION_VALUES(vtkVIMLOPPrintValueOption)
  VIMLOP_REGISTRATION_SWITCHES(vtkVIMLOPPrintSwitchOption)
  os << indent << "InitialTransform: " << this->InitialTransform.Get() << "\n";
  os << indent << "Starts: " << (this->Starts ? this->Starts->GetNumberOfItems() : 0) << "\n";
  os << indent << "StartFromCanonicalPoses: " << (this->StartFromCanonicalPoses ? "On" : "Off")
     << "\n";
  os << indent << "InitialScale: " << this->InitialScale << "\n";
  os << indent << "FailureThresholdPx: " << this->MultiStart.failureContourErrorPx << "\n";
  os << indent << "FailureResidualMm: " << this->MultiStart.failureResidualErrorMm << "\n";
  os << indent << "Transform: " << this->Transform.Get() << "\n";
  os << indent << "Result: " << vimlop::toString(this->Result.termination) << " after "
     << this->Result.iterations << " iterations, residual " << this->Result.residualErrorMm
     << " mm, contour error " << this->Result.contourErrorPx << " px"
     << (this->Outcome.failure ? ", FLAGGED AS A FAILURE" : "") << "\n";
}
