// A navigation-software stand-in that uses only the installed VIMLOP package:
// it makes a synthetic P1 trial (DESIGN P1) on a model built in memory, feeds
// it to a VTK pipeline around vtkVIMLOPRegistration, prints the transform
// GetTransform() offers and checks it against the trial's ground truth. The
// exit code is 0 only when the registration is accurate.
#include <vimlop/Core/Error.h>
#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Pipeline/vtkVIMLOPVideoRegistration.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Registration/RegistrationInputConversion.h>
#include <vimlop/Registration/vtkVIMLOPRegistration.h>

#include <vtkLinearTransform.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTable.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>

#include <cmath>
#include <cstdio>

namespace
{

/// A closed, bumpy cavity with a solid blob inside (normals into the air):
/// no symmetry the registration could slide along.
vimlop::TriangleMesh makeModel()
{
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> faces;
  auto addSphere = [&](const Eigen::Vector3d& centre, double radius, bool cavity)
  {
    const int rings = 40;
    const int segments = 80;
    const int first = static_cast<int>(vertices.size());
    for (int i = 0; i <= rings; ++i)
    {
      const double theta = M_PI * i / rings;
      for (int j = 0; j < segments; ++j)
      {
        const double phi = 2.0 * M_PI * j / segments;
        const double bump = cavity ? 1.0 + 0.15 * std::sin(3 * theta) * std::cos(2 * phi) : 1.0;
        vertices.push_back(centre +
          radius * bump *
            Eigen::Vector3d(
              std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
      }
    }
    for (int i = 0; i < rings; ++i)
    {
      for (int j = 0; j < segments; ++j)
      {
        const int a = first + i * segments + j;
        const int b = first + i * segments + (j + 1) % segments;
        const int c = a + segments;
        const int d = b + segments;
        // Outward winding (a, c, d), reversed for the cavity so normals face the air.
        if (i > 0)
          faces.push_back(cavity ? Eigen::Vector3i(a, b, c) : Eigen::Vector3i(a, c, b));
        if (i < rings - 1)
          faces.push_back(cavity ? Eigen::Vector3i(b, d, c) : Eigen::Vector3i(b, c, d));
      }
    }
  };
  addSphere(Eigen::Vector3d::Zero(), 20.0, true);
  addSphere(Eigen::Vector3d(8.0, 0.0, 3.0), 4.0, false);
  return vimlop::TriangleMesh(vertices, faces);
}

vtkNew<vtkTransform> toVtk(const vimlop::SimilarityTransform& transform)
{
  vtkNew<vtkTransform> result;
  const Eigen::Matrix4d m = transform.matrix();
  double elements[16];
  for (int i = 0; i < 16; ++i)
  {
    elements[i] = m(i / 4, i % 4);
  }
  result->SetMatrix(elements);
  return result;
}

} // namespace

int main()
{
  // The data: the model and a P1 trial on it (Core and Raycast make the data).
  const vimlop::TriangleMesh mesh = makeModel();
  vimlop::SyntheticOptions synthetic;
  synthetic.points = 400;
  const vimlop::SyntheticTrial trial =
    vimlop::makeSyntheticTrial(vimlop::makeEmbreeRegistrationModel(mesh), synthetic, 3);

  // The VTK side: the four inputs in the layouts of the filter's ports.
  const vtkSmartPointer<vtkPolyData> model = vimlop::toPolyData(mesh);
  const vtkSmartPointer<vtkPolyData> points = vimlop::makeSfmPointPolyData(trial.data);
  const vtkSmartPointer<vtkTable> frames = vimlop::makeFrameTable(trial.data.frames);
  const vtkSmartPointer<vtkPolyData> contours = vimlop::makeContourPolyData(trial.data.frames);
  const vtkNew<vtkTransform> start = toVtk(trial.initialSfmToCT);

  vtkNew<vtkVIMLOPRegistration> registration;
  registration->SetModelData(model);
  registration->SetPointsData(points);
  registration->SetFramesData(frames);
  registration->SetContoursData(contours);
  registration->SetInitialTransform(start);
  registration->SetMinScale(0.8);
  registration->SetMaxScale(1.25);

  // Downstream, SfM-frame data follows the live transform.
  vtkNew<vtkTransformPolyDataFilter> pointsInCT;
  pointsInCT->SetInputData(points);
  pointsInCT->SetTransform(registration->GetTransform());

  registration->Update();
  pointsInCT->Update();

  vtkMatrix4x4* matrix = registration->GetTransform()->GetMatrix();
  std::printf("vtkVIMLOPRegistration::GetTransform() (SfM to CT, mm):\n");
  for (int i = 0; i < 4; ++i)
  {
    std::printf("  %10.5f %10.5f %10.5f %10.4f\n", matrix->GetElement(i, 0),
      matrix->GetElement(i, 1), matrix->GetElement(i, 2), matrix->GetElement(i, 3));
  }
  const double scale = std::cbrt(matrix->Determinant());

  // Target registration error through the VTK transform: each target taken
  // back into the SfM frame by the truth, then into the CT by the estimate.
  const vimlop::SimilarityTransform truthInverse = trial.truthSfmToCT.inverse();
  double tre = 0.0;
  for (const Eigen::Vector3d& target : trial.targetsCT)
  {
    const Eigen::Vector3d sfm = truthInverse.apply(target);
    double mapped[3];
    registration->GetTransform()->TransformPoint(sfm.data(), mapped);
    tre += (Eigen::Vector3d(mapped[0], mapped[1], mapped[2]) - target).norm();
  }
  tre /= static_cast<double>(trial.targetsCT.size());

  // The transformed SfM points against their true positions in CT.
  vtkPoints* moved = pointsInCT->GetOutput()->GetPoints();
  double pointError = 0.0;
  for (vtkIdType i = 0; i < moved->GetNumberOfPoints(); ++i)
  {
    const Eigen::Vector3d truth =
      trial.truthSfmToCT.apply(trial.data.points[static_cast<size_t>(i)]);
    double p[3];
    moved->GetPoint(i, p);
    pointError += (Eigen::Vector3d(p[0], p[1], p[2]) - truth).norm();
  }
  pointError /= static_cast<double>(std::max<vtkIdType>(1, moved->GetNumberOfPoints()));

  const vtkIdType cameras = registration->GetCameraPoses()->GetNumberOfRows();
  std::printf("scale %.4f (truth %.4f), %d iterations, %lld camera poses\n", scale,
    trial.truthSfmToCT.scale, registration->GetNumberOfIterations(),
    static_cast<long long>(cameras));
  std::printf(
    "TRE %.4f mm over %zu targets; SfM points moved by the transform: %.4f mm from the truth "
    "on average\n",
    tre, trial.targetsCT.size(), pointError);
  const bool accurate = tre < 0.5 && pointError < 0.5 && cameras == 6 &&
    moved->GetNumberOfPoints() == static_cast<vtkIdType>(trial.data.points.size());
  std::printf("%s\n", accurate ? "accurate" : "NOT ACCURATE");

  // Options set here and read by the library: the struct must have one
  // layout on both sides, whatever flags this program is built with.
  vimlop::RegistrationOptions options;
  options.minScale = 0.5;
  options.maxScale = 2.0;
  options.threads = 1;
  bool optionsRead = true;
  try
  {
    options.validate();
  }
  catch (const vimlop::Error& e)
  {
    std::printf("the library read other options than this program set: %s\n", e.what());
    optionsRead = false;
  }

  // The main job's VTK face (its header pulls in the option tables) starts
  // from the defaults the filter has.
  vtkNew<vtkVIMLOPVideoRegistration> mainJob;
  const bool sameDefaults =
    mainJob->GetMaxIterations() == vtkNew<vtkVIMLOPRegistration>()->GetMaxIterations() &&
    mainJob->GetFailureThresholdPx() == registration->GetFailureThresholdPx();
  std::printf("the main job's VTK face has %s defaults\n", sameDefaults ? "the same" : "OTHER");
  return accurate && sameDefaults && optionsRead ? 0 : 1;
}
