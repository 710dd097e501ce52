#include <vimlop/Pipeline/vtkVIMLOPVideoRegistration.h>

#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Pipeline/RegistrationOutputs.h>
#include <vimlop/Pipeline/VideoRegistrationOptions.h>
#include <vimlop/Registration/vtkVIMLOPRegistration.h>

#include <gtest/gtest.h>

#include <vtkCallbackCommand.h>
#include <vtkDataArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkTable.h>

#include <filesystem>
#include <map>
#include <string>

namespace vimlop
{
namespace
{

namespace fs = std::filesystem;

/// The sequence written by the CLI test vimlop.simulate.cranium-upright.
const fs::path simulation = fs::path(VIMLOP_TEST_OUTPUT_DIR) / "sim-cranium-30";

void keepError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  *static_cast<std::string*>(clientData) = static_cast<const char*>(callData);
}

TEST(vtkVIMLOPVideoRegistration, RegistersFromCanonicalPosesWithTheMainJobsDefaults)
{
  vtkNew<vtkVIMLOPVideoRegistration> registration;
  registration->SetCTFileName(VIMLOP_CRANIUM);
  registration->SetFramesPath((simulation / "frames").string().c_str());
  registration->SetIntrinsicsFileName((simulation / "intrinsics.yaml").string().c_str());
  registration->SetTrackerFileName((simulation / "tracker.csv").string().c_str());
  std::string error;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(keepError);
  onError->SetClientData(&error);
  registration->AddObserver(vtkCommand::ErrorEvent, onError);
  registration->Update();
  ASSERT_TRUE(error.empty()) << error;

  // Every registered frame's camera against the simulation's truth.
  std::map<int, CameraPose> truth;
  for (const FramePose& p : readFramePoses((simulation / "truth" / "poses.json").string()))
  {
    truth[p.frameId] = p.cameraToWorld;
  }
  vtkTable* poses = registration->GetCameraPoses();
  ASSERT_GE(poses->GetNumberOfRows(), 20);
  auto* ids = vtkIntArray::SafeDownCast(poses->GetColumnByName("FrameId"));
  vtkDataArray* matrices = vtkDataArray::SafeDownCast(poses->GetColumnByName("CameraToCT"));
  ASSERT_TRUE(ids && matrices);
  double sum = 0.0;
  for (vtkIdType row = 0; row < poses->GetNumberOfRows(); ++row)
  {
    Eigen::Matrix<double, 4, 4, Eigen::RowMajor> m;
    matrices->GetTuple(row, m.data());
    CameraPose estimate;
    estimate.rotation = m.topLeftCorner<3, 3>();
    estimate.centre = m.topRightCorner<3, 1>();
    sum += cameraPositionError(estimate, truth.at(ids->GetValue(row)));
  }
  const double meanErrorMm = sum / poses->GetNumberOfRows();
  EXPECT_LT(meanErrorMm, 1.0);
  EXPECT_FALSE(registration->GetFlaggedAsFailure());
  EXPECT_GT(registration->GetNumberOfCandidates(), 100);
  EXPECT_LT(registration->GetContourErrorPx(), registration->GetFailureThresholdPx());
}

TEST(vtkVIMLOPVideoRegistration, MissingFramesAreAnErrorThatSaysWhich)
{
  vtkNew<vtkVIMLOPVideoRegistration> registration;
  registration->SetCTFileName(VIMLOP_CRANIUM);
  registration->SetFramesPath((simulation / "no-such-folder").string().c_str());
  registration->SetIntrinsicsFileName((simulation / "intrinsics.yaml").string().c_str());
  registration->SetInitialScale(0.5);
  std::string error;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(keepError);
  onError->SetClientData(&error);
  registration->AddObserver(vtkCommand::ErrorEvent, onError);
  registration->Update();
  EXPECT_NE(error.find("no-such-folder"), std::string::npos) << error;
  EXPECT_FALSE(registration->GetFlaggedAsFailure());
  EXPECT_EQ(registration->GetNumberOfRegisteredFrames(), 0);
}

TEST(vtkVIMLOPVideoRegistration, ItsDefaultsAreThoseOfTheRegistrationFilterAndThePipeline)
{
  vtkNew<vtkVIMLOPVideoRegistration> video;
  vtkNew<vtkVIMLOPRegistration> filter;
  const VideoRegistrationOptions defaults;
  EXPECT_EQ(video->GetOptionsAsJSON(), registrationOptionsJson(defaults).dump(2));
  // The registration filter's options, in result.json's layout, are the pipeline's.
  VideoRegistrationOptions filterOptions;
  filterOptions.registration = filter->GetRegistrationOptions();
  EXPECT_EQ(
    registrationOptionsJson(filterOptions).dump(), registrationOptionsJson(defaults).dump());
  EXPECT_DOUBLE_EQ(filter->GetFailureThresholdPx(), defaults.multiStart.failureContourErrorPx);
}

} // namespace
} // namespace vimlop
