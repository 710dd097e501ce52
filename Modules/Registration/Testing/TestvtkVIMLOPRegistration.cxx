#include "CraniumAirway.h"
#include "TestMeshes.h"
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Registration/RegistrationInputConversion.h>
#include <vimlop/Registration/vtkVIMLOPRegistration.h>

#include "TestFolders.h"

#include <gtest/gtest.h>

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTable.h>
#include <vtkTransform.h>
#include <vtkTransformCollection.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLTableReader.h>
#include <vtkXMLTableWriter.h>

#include <filesystem>
#include <sstream>
#include <string>

using namespace vimlop;

namespace
{

/// Counts events and keeps the last message and iteration record.
struct EventLog
{
  int progress = 0;
  int iterations = 0;
  int lastIteration = 0;
  bool increasing = true;
  std::string error;
  std::string warning;
  int abortAfter = 0; ///< when positive, set AbortExecute at that iteration
};

void logEvent(vtkObject* caller, unsigned long event, void* clientData, void* callData)
{
  auto* log = static_cast<EventLog*>(clientData);
  if (event == vtkCommand::ProgressEvent)
  {
    ++log->progress;
  }
  else if (event == vtkVIMLOPRegistration::IterationEvent)
  {
    const auto* record = static_cast<const IterationRecord*>(callData);
    log->increasing = log->increasing && record->iteration > log->lastIteration;
    log->lastIteration = record->iteration;
    ++log->iterations;
    if (log->abortAfter > 0 && record->iteration >= log->abortAfter)
    {
      static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
    }
  }
  else if (event == vtkCommand::ErrorEvent)
  {
    log->error = static_cast<const char*>(callData);
  }
  else if (event == vtkCommand::WarningEvent)
  {
    log->warning = static_cast<const char*>(callData);
  }
}

void observe(vtkVIMLOPRegistration* registration, EventLog& log)
{
  vtkNew<vtkCallbackCommand> command;
  command->SetCallback(logEvent);
  command->SetClientData(&log);
  for (unsigned long event : { static_cast<unsigned long>(vtkCommand::ProgressEvent),
         static_cast<unsigned long>(vtkVIMLOPRegistration::IterationEvent),
         static_cast<unsigned long>(vtkCommand::ErrorEvent),
         static_cast<unsigned long>(vtkCommand::WarningEvent) })
  {
    registration->AddObserver(event, command);
  }
}

SimilarityTransform transformOf(vtkLinearTransform* transform)
{
  Eigen::Matrix<double, 4, 4, Eigen::RowMajor> m;
  std::copy(
    &transform->GetMatrix()->Element[0][0], &transform->GetMatrix()->Element[0][0] + 16, m.data());
  return SimilarityTransform::fromMatrix(m, 1e-6);
}

void writeVtp(vtkPolyData* data, const std::string& path)
{
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(data);
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1) << path;
}

void writeVtt(vtkTable* table, const std::string& path)
{
  vtkNew<vtkXMLTableWriter> writer;
  writer->SetInputData(table);
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1) << path;
}

/// A small P1-like problem on the in-memory cavity (fast).
SyntheticTrial fixtureTrial(const TriangleMesh& mesh)
{
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  SyntheticOptions options;
  options.points = 300;
  return makeSyntheticTrial(model, options, 11);
}

void connect(vtkVIMLOPRegistration* registration, const TriangleMesh& mesh,
  const RegistrationData& data, bool withNormals = true)
{
  vtkSmartPointer<vtkPolyData> surface = toPolyData(mesh);
  if (!withNormals)
  {
    surface->GetCellData()->RemoveArray("Normals");
  }
  registration->SetModelData(surface);
  registration->SetPointsData(makeSfmPointPolyData(data));
  registration->SetFramesData(makeFrameTable(data.frames));
  registration->SetContoursData(makeContourPolyData(data.frames));
}

} // namespace

TEST(vtkVIMLOPRegistration, RecoversP1InAPipelineAndFollowsParameterChanges)
{
  // P1 data on the real airway, written to files and read back by VTK readers.
  const TriangleMesh mesh = fixtures::craniumAirwayMesh();
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  const SyntheticTrial trial = makeSyntheticTrial(model, SyntheticOptions(), 3);
  const std::string dir = fixtures::freshTestFolder("pipeline-p1").string();
  writeVtp(toPolyData(mesh), dir + "/model.vtp");
  writeVtp(makeSfmPointPolyData(trial.data), dir + "/sfm-points.vtp");
  writeVtt(makeFrameTable(trial.data.frames), dir + "/frame-table.vtt");
  writeVtp(makeContourPolyData(trial.data.frames), dir + "/video-contours.vtp");

  vtkNew<vtkXMLPolyDataReader> modelReader;
  modelReader->SetFileName((dir + "/model.vtp").c_str());
  vtkNew<vtkXMLPolyDataReader> pointReader;
  pointReader->SetFileName((dir + "/sfm-points.vtp").c_str());
  vtkNew<vtkXMLTableReader> frameReader;
  frameReader->SetFileName((dir + "/frame-table.vtt").c_str());
  vtkNew<vtkXMLPolyDataReader> contourReader;
  contourReader->SetFileName((dir + "/video-contours.vtp").c_str());

  vtkNew<vtkVIMLOPRegistration> registration;
  registration->SetModelConnection(modelReader->GetOutputPort());
  registration->SetPointsConnection(pointReader->GetOutputPort());
  registration->SetFramesConnection(frameReader->GetOutputPort());
  registration->SetContoursConnection(contourReader->GetOutputPort());
  registration->SetMinScale(0.8); // as the P1 evaluation does
  registration->SetMaxScale(1.25);
  EventLog log;
  observe(registration, log);

  // Downstream: SfM-frame data mapped by the live transform, and an actor.
  vtkLinearTransform* live = registration->GetTransform();
  vtkNew<vtkTransformPolyDataFilter> mapped;
  mapped->SetInputConnection(pointReader->GetOutputPort());
  mapped->SetTransform(live);
  vtkNew<vtkActor> actor;
  actor->SetUserTransform(live);

  registration->Update();
  ASSERT_TRUE(log.error.empty()) << log.error;
  mapped->Update();
  const SimilarityTransform first = transformOf(live);
  const double tre = targetRegistrationError(first, trial.truthSfmToCT, trial.targetsCT);
  std::cout << "pipeline P1 (seed 3): TRE " << tre << " mm after "
            << registration->GetNumberOfIterations() << " iterations ("
            << toString(registration->GetTerminationReason()) << ")\n";
  EXPECT_LT(tre, 0.25); // the paper's P1: 0.2 mm
  EXPECT_GT(log.iterations, 3);
  EXPECT_TRUE(log.increasing);
  EXPECT_GE(log.progress, log.iterations);
  EXPECT_LE(log.iterations, registration->GetNumberOfIterations());

  // The outputs agree with the transform.
  vtkPolyData* registered = registration->GetRegisteredPoints();
  ASSERT_EQ(registered->GetNumberOfPoints(), static_cast<vtkIdType>(trial.data.points.size()));
  ASSERT_EQ(mapped->GetOutput()->GetNumberOfPoints(), registered->GetNumberOfPoints());
  for (vtkIdType i = 0; i < registered->GetNumberOfPoints(); i += 37)
  {
    double a[3], b[3];
    registered->GetPoint(i, a);
    mapped->GetOutput()->GetPoint(i, b);
    EXPECT_NEAR(a[0], b[0], 1e-4);
    EXPECT_NEAR(a[1], b[1], 1e-4);
    EXPECT_NEAR(a[2], b[2], 1e-4);
  }
  vtkTable* cameras = registration->GetCameraPoses();
  ASSERT_EQ(cameras->GetNumberOfRows(), static_cast<vtkIdType>(trial.data.frames.size()));
  for (vtkIdType row = 0; row < cameras->GetNumberOfRows(); ++row)
  {
    EXPECT_LT(cameras->GetValueByName(row, "ContourErrorInliersPx").ToDouble(), 2.0);
    EXPECT_LT(cameras->GetValueByName(row, "ContourErrorPx").ToDouble(), 5.0);
    EXPECT_GT(cameras->GetValueByName(row, "InlierContourPoints").ToInt(), 10);
  }
  EXPECT_GT(registration->GetCorrespondences()->GetNumberOfLines(), 100);
  EXPECT_LT((Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(
               &actor->GetMatrix()->Element[0][0]) -
              first.matrix())
              .norm(),
    1e-9);

  // Nothing changed: no re-execution.
  const int iterationsSoFar = log.iterations;
  registration->Update();
  EXPECT_EQ(log.iterations, iterationsSoFar);

  // A parameter change re-executes; the same transform object follows.
  registration->SetMethodToIMLP();
  registration->Update();
  ASSERT_TRUE(log.error.empty()) << log.error;
  EXPECT_GT(log.iterations, iterationsSoFar);
  EXPECT_EQ(registration->GetTransform(), live);
  const SimilarityTransform imlp = transformOf(live);
  EXPECT_GT((imlp.matrix() - first.matrix()).norm(), 1e-6);
  EXPECT_LT(targetRegistrationError(imlp, trial.truthSfmToCT, trial.targetsCT), 1.0);
  mapped->Update();
  double a[3], b[3];
  registration->GetRegisteredPoints()->GetPoint(5, a);
  mapped->GetOutput()->GetPoint(5, b);
  EXPECT_NEAR(a[0], b[0], 1e-4);
  EXPECT_LT((Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(
               &actor->GetMatrix()->Element[0][0]) -
              imlp.matrix())
              .norm(),
    1e-9);

  // Back to V-IMLOP: the same result as the first time.
  registration->SetMethodToVIMLOP();
  registration->Update();
  EXPECT_LT((transformOf(live).matrix() - first.matrix()).norm(), 1e-9);
}

TEST(vtkVIMLOPRegistration, StartsFromTheInitialTransformAndReexecutesWhenItChanges)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  SyntheticTrial trial = fixtureTrial(mesh);
  vtkNew<vtkVIMLOPRegistration> registration;
  connect(registration, mesh, trial.data);
  registration->SetMethodToIMLP();
  registration->SetMaxIterations(1);
  registration->SetAnatomicalConstraint(false); // any start will do here
  vtkNew<vtkTransform> initial;
  registration->SetInitialTransform(initial);
  registration->Update();
  const SimilarityTransform fromIdentity = registration->GetResult().history.front().transform;
  EXPECT_LT((fromIdentity.matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-12);
  // Moving the initial transform (not the filter) is enough to re-execute.
  initial->Translate(0.5, 0.0, 0.0);
  registration->Update();
  EXPECT_NEAR(registration->GetResult().history.front().transform.translation.x(), 0.5, 1e-12);
}

TEST(vtkVIMLOPRegistration, TheZBufferBackendRegistersLikeEmbree)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  const SyntheticTrial trial = fixtureTrial(mesh);
  vtkNew<vtkVIMLOPRegistration> registration;
  connect(registration, mesh, trial.data);
  registration->SetMinScale(0.8);
  registration->SetMaxScale(1.25);
  registration->Update();
  const double treEmbree =
    targetRegistrationError(registration->GetResult().sfmToCT, trial.truthSfmToCT, trial.targetsCT);
  registration->SetVisibilityBackend(vtkVIMLOPRegistration::VisibilityBackend::ZBuffer);
  registration->Update();
  const double treZBuffer =
    targetRegistrationError(registration->GetResult().sfmToCT, trial.truthSfmToCT, trial.targetsCT);
  EXPECT_LT(treEmbree, 0.5);
  EXPECT_LT(treZBuffer, 0.5);
  EXPECT_LT(std::abs(treEmbree - treZBuffer), 0.1);
}

TEST(vtkVIMLOPRegistration, AbortExecuteStopsAfterTheCurrentIteration)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  const SyntheticTrial trial = fixtureTrial(mesh);
  vtkNew<vtkVIMLOPRegistration> registration;
  connect(registration, mesh, trial.data);
  EventLog log;
  log.abortAfter = 2;
  observe(registration, log);
  registration->Update();
  EXPECT_EQ(registration->GetTerminationReason(), TerminationReason::Cancelled);
  EXPECT_EQ(registration->GetNumberOfIterations(), 2);
  EXPECT_EQ(log.iterations, 2);
  // The outputs hold the last estimate.
  EXPECT_EQ(registration->GetRegisteredPoints()->GetNumberOfPoints(),
    static_cast<vtkIdType>(trial.data.points.size()));

  // The next execution starts afresh.
  log.abortAfter = 0;
  registration->Modified();
  registration->Update();
  EXPECT_NE(registration->GetTerminationReason(), TerminationReason::Cancelled);
  EXPECT_GT(registration->GetNumberOfIterations(), 2);
}

TEST(vtkVIMLOPRegistration, ReportsMissingInputs)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  const SyntheticTrial trial = fixtureTrial(mesh);
  vtkNew<vtkVIMLOPRegistration> registration;
  EventLog log;
  observe(registration, log);
  registration->SetPointsData(makeSfmPointPolyData(trial.data));
  registration->Update();
  EXPECT_NE(log.error.find("no model surface on input port 0"), std::string::npos) << log.error;

  log.error.clear();
  registration->SetModelData(toPolyData(mesh));
  registration->SetPointsData(nullptr);
  registration->Update();
  EXPECT_NE(log.error.find("no SfM points on input port 1"), std::string::npos) << log.error;

  log.error.clear();
  registration->SetPointsData(makeSfmPointPolyData(trial.data));
  registration->Update();
  EXPECT_NE(log.error.find("V-IMLOP needs the frame table on input port 2 and the video contours "
                           "on input port 3"),
    std::string::npos)
    << log.error;

  // IMLP registers the points alone.
  log.error.clear();
  registration->SetMethodToIMLP();
  registration->Update();
  EXPECT_TRUE(log.error.empty()) << log.error;
  EXPECT_GT(registration->GetNumberOfIterations(), 0);
}

TEST(vtkVIMLOPRegistration, ReportsAFrameTableThatDisagreesWithTheContours)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  SyntheticTrial trial = fixtureTrial(mesh);
  vtkNew<vtkVIMLOPRegistration> registration;
  connect(registration, mesh, trial.data);
  // The table loses its last frame; the contours still have it.
  std::vector<VideoFrame> fewer(trial.data.frames.begin(), trial.data.frames.end() - 1);
  registration->SetFramesData(makeFrameTable(fewer));
  EventLog log;
  observe(registration, log);
  registration->Update();
  const std::string expected = "video contours: point " +
    std::to_string(trial.data.numberOfContourPoints() - trial.data.frames.back().contour.size()) +
    " belongs to frame " + std::to_string(trial.data.frames.back().frameId) +
    ", which the frame table (" + std::to_string(fewer.size()) + " rows) does not have";
  EXPECT_NE(log.error.find(expected), std::string::npos) << log.error;

  // A malformed column is named.
  log.error.clear();
  vtkSmartPointer<vtkTable> table = makeFrameTable(trial.data.frames);
  table->RemoveColumnByName("Fx");
  registration->SetFramesData(table);
  registration->Update();
  EXPECT_NE(log.error.find("frame table: missing numeric column 'Fx'"), std::string::npos)
    << log.error;
}

TEST(vtkVIMLOPRegistration, ComputesMissingNormalsWithAWarning)
{
  // Normals into the air, but the file lost them and its faces are reversed.
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  const SyntheticTrial trial = fixtureTrial(mesh);
  vtkNew<vtkVIMLOPRegistration> registration;
  connect(registration, mesh.flipped(), trial.data, /*withNormals=*/false);
  registration->SetMinScale(0.8);
  registration->SetMaxScale(1.25);
  EventLog log;
  observe(registration, log);
  registration->Update();
  EXPECT_NE(log.warning.find("the model surface has no 'Normals' cell array; computed consistent "
                             "face normals pointing into the air it encloses"),
    std::string::npos)
    << log.warning;
  EXPECT_TRUE(log.error.empty()) << log.error;
  EXPECT_LT(
    targetRegistrationError(registration->GetResult().sfmToCT, trial.truthSfmToCT, trial.targetsCT),
    0.5);
}

TEST(vtkVIMLOPRegistration, ReportsBadDataAndOptions)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  const SyntheticTrial trial = fixtureTrial(mesh);
  vtkNew<vtkVIMLOPRegistration> registration;
  connect(registration, mesh, trial.data);
  EventLog log;
  observe(registration, log);

  // A covariance array of the wrong shape.
  vtkSmartPointer<vtkPolyData> points = makeSfmPointPolyData(trial.data);
  vtkNew<vtkIntArray> wrong;
  wrong->SetName("Covariance");
  wrong->SetNumberOfComponents(6);
  wrong->SetNumberOfTuples(points->GetNumberOfPoints());
  points->GetPointData()->AddArray(wrong);
  registration->SetPointsData(points);
  registration->Update();
  EXPECT_NE(log.error.find("SfM points: the 'Covariance' array has 6 components; expected 9"),
    std::string::npos)
    << log.error;

  // An initial transform that is not a similarity.
  log.error.clear();
  registration->SetPointsData(makeSfmPointPolyData(trial.data));
  vtkNew<vtkTransform> shear;
  shear->Scale(1.0, 2.0, 1.0);
  registration->SetInitialTransform(shear);
  registration->Update();
  EXPECT_NE(log.error.find("the initial transform is not a similarity"), std::string::npos)
    << log.error;

  // Core's own checks come through: scale bounds that exclude the start.
  log.error.clear();
  registration->SetInitialTransform(nullptr);
  registration->SetMinScale(2.0);
  registration->SetMaxScale(3.0);
  registration->Update();
  EXPECT_NE(log.error.find("lies outside the scale bounds"), std::string::npos) << log.error;
}

TEST(vtkVIMLOPRegistration, OptionsDefaultToCoreAndArePrinted)
{
  vtkNew<vtkVIMLOPRegistration> registration;
  const RegistrationOptions defaults;
  const RegistrationOptions& o = registration->GetRegistrationOptions();
  EXPECT_EQ(o.method, defaults.method);
  EXPECT_EQ(o.maxIterations, defaults.maxIterations);
  EXPECT_DOUBLE_EQ(registration->GetMaxContourNormalAngleDeg(), 45.0);
  EXPECT_DOUBLE_EQ(registration->GetContourKappa(), 200.0);
  double covariance[3];
  registration->GetContourPositionCovariancePx2(covariance);
  // Σ2d of contours detected in video (the main job's default, 1 px²).
  EXPECT_DOUBLE_EQ(covariance[0], 1.0);
  EXPECT_DOUBLE_EQ(covariance[1], 0.0);
  EXPECT_DOUBLE_EQ(covariance[2], 1.0);
  EXPECT_FALSE(registration->GetStartFromCanonicalPoses());
  EXPECT_DOUBLE_EQ(
    registration->GetFailureThresholdPx(), MultiStartOptions().failureContourErrorPx);
  EXPECT_DOUBLE_EQ(
    registration->GetFailureResidualMm(), MultiStartOptions().failureResidualErrorMm);
  EXPECT_EQ(registration->GetVisibilityBackend(), vtkVIMLOPRegistration::VisibilityBackend::Embree);

  const vtkMTimeType before = registration->GetMTime();
  registration->SetTrimFraction(defaults.trimFraction); // unchanged: not modified
  EXPECT_EQ(registration->GetMTime(), before);
  registration->SetTrimFraction(0.2);
  registration->SetMaxContourNormalAngleDeg(30.0);
  EXPECT_GT(registration->GetMTime(), before);
  EXPECT_DOUBLE_EQ(registration->GetRegistrationOptions().trimFraction, 0.2);
  EXPECT_DOUBLE_EQ(registration->GetRegistrationOptions().contourMatch.maxAngleDeg, 30.0);

  std::ostringstream printed;
  registration->Print(printed);
  EXPECT_NE(printed.str().find("TrimFraction: 0.2"), std::string::npos);
  EXPECT_NE(printed.str().find("Method: vimlop"), std::string::npos);
  EXPECT_NE(printed.str().find("MaxContourNormalAngleDeg: 30"), std::string::npos);
}

TEST(vtkVIMLOPRegistration, ItsTableGeneratedSettersClampIntoTheTableRangeAndReachCoreOptions)
{
  vtkNew<vtkVIMLOPRegistration> registration;
  registration->SetTrimFraction(5.0);
  EXPECT_DOUBLE_EQ(registration->GetTrimFraction(), registration->GetTrimFractionMaxValue());
  registration->SetMaxIterations(-3);
  EXPECT_EQ(registration->GetMaxIterations(), 1);
  EXPECT_EQ(registration->GetMaxIterationsMinValue(), 1);
  registration->SetNumberOfThreads(1);
  registration->AnatomicalConstraintOff();
  registration->SetStallIterations(7);
  const RegistrationOptions& o = registration->GetRegistrationOptions();
  EXPECT_DOUBLE_EQ(o.trimFraction, 0.9);
  EXPECT_EQ(o.threads, 1);
  EXPECT_FALSE(o.anatomicalConstraint);
  EXPECT_EQ(o.stallIterations, 7);
  // Whatever the setters accept, Core accepts: the ranges are the same table.
  EXPECT_NO_THROW(o.validate());
  std::ostringstream printed;
  registration->Print(printed);
  EXPECT_NE(printed.str().find("AnatomicalConstraint: Off"), std::string::npos);
  EXPECT_NE(printed.str().find("StallIterations: 7"), std::string::npos);
}

TEST(vtkVIMLOPRegistration, AMultiStartKeepsTheLeastContourErrorAndFlagsAboveTheThreshold)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  const SyntheticTrial trial = fixtureTrial(mesh);
  vtkNew<vtkVIMLOPRegistration> registration;
  connect(registration, mesh, trial.data);
  registration->SetMinScale(0.8);
  registration->SetMaxScale(1.25);
  // The trial's start, and the same start turned by 40 degrees about the
  // data: the multi-start must keep the good one.
  vtkNew<vtkTransform> good;
  good->SetMatrix(
    Eigen::Matrix<double, 4, 4, Eigen::RowMajor>(trial.initialSfmToCT.matrix()).data());
  vtkNew<vtkTransform> turned;
  turned->PostMultiply();
  turned->SetMatrix(good->GetMatrix());
  const Eigen::Vector3d centre = trial.initialSfmToCT.apply(trial.data.points.front());
  turned->Translate(-centre.x(), -centre.y(), -centre.z());
  turned->RotateZ(40.0);
  turned->Translate(centre.x(), centre.y(), centre.z());
  vtkNew<vtkTransformCollection> starts;
  starts->AddItem(turned);
  starts->AddItem(good);
  registration->SetStarts(starts);
  EventLog log;
  observe(registration, log);
  registration->Update();
  ASSERT_TRUE(log.error.empty()) << log.error;
  // Two starts, each at the three scale factors (some may be skipped: a
  // camera outside the airway).
  EXPECT_EQ(registration->GetNumberOfCandidates(), 6);
  EXPECT_LT(
    targetRegistrationError(registration->GetResult().sfmToCT, trial.truthSfmToCT, trial.targetsCT),
    0.5);
  EXPECT_FALSE(registration->GetFlaggedAsFailure());
  EXPECT_GT(log.progress, 2);
  const double contourErrorPx = registration->GetContourErrorPx();

  // A threshold below the winner's contour error flags it (and re-executes).
  registration->SetFailureThresholdPx(0.5 * contourErrorPx);
  registration->Update();
  EXPECT_TRUE(registration->GetFlaggedAsFailure());
  std::ostringstream printed;
  registration->Print(printed);
  EXPECT_NE(printed.str().find("FLAGGED AS A FAILURE"), std::string::npos);

  // So does a threshold on the 3-D residual below the winner's residual.
  registration->SetFailureThresholdPx(2.0 * contourErrorPx);
  registration->SetFailureResidualMm(0.5 * registration->GetResidualErrorMm());
  registration->Update();
  EXPECT_TRUE(registration->GetFlaggedAsFailure());
  registration->SetFailureResidualMm(2.0 * registration->GetResidualErrorMm());
  registration->Update();
  EXPECT_FALSE(registration->GetFlaggedAsFailure());
}

TEST(vtkVIMLOPRegistration, CanonicalStartsWithoutAnInitialScaleAreAnError)
{
  const TriangleMesh mesh = fixtures::makeCavityWithBlobs();
  const SyntheticTrial trial = fixtureTrial(mesh);
  vtkNew<vtkVIMLOPRegistration> registration;
  connect(registration, mesh, trial.data);
  registration->StartFromCanonicalPosesOn();
  EventLog log;
  observe(registration, log);
  registration->Update();
  EXPECT_NE(
    log.error.find("canonical starts need InitialScale (mm per SfM unit)"), std::string::npos)
    << log.error;
  EXPECT_FALSE(registration->GetFlaggedAsFailure());
}
