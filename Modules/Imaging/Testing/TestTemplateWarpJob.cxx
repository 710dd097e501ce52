#include "AirwayPhantom.h"
#include "TestFolders.h"
#include "TestMeshes.h"
#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/DisplacementField.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Imaging/TemplateWarpJob.h>

#include <gtest/gtest.h>

#include <vtkPolyData.h>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace vimlop;
using fixtures::HeadPhantom;

namespace
{

namespace fs = std::filesystem;

std::string jobError(const TemplateWarpJobOptions& options)
{
  try
  {
    runTemplateWarpJob(options);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(TemplateWarpJob, CarriesAMeshAndAPoseIntoAShiftedPatient)
{
  const fs::path out = fixtures::freshTestFolder("template-warp-job");
  // The patient is the template phantom moved by `shiftMm`: the same voxels
  // on a grid whose origin moved, so template point x is patient point x + shift.
  const Eigen::Vector3d shiftMm(2.5, -1.5, 1.25);
  CTVolume templateCT = HeadPhantom::make();
  // A smooth texture (periods of about 10 mm) in every voxel: without it the
  // phantom's flat regions leave the mutual information too little to hold on to.
  std::size_t n = 0;
  for (int k = 0; k < templateCT.dims[2]; ++k)
  {
    for (int j = 0; j < templateCT.dims[1]; ++j)
    {
      for (int i = 0; i < templateCT.dims[0]; ++i, ++n)
      {
        templateCT.intensities[n] += static_cast<float>(
          75.0 * (1.0 + std::sin(0.6 * i) * std::sin(0.7 * j) * std::sin(0.5 * k)));
      }
    }
  }
  CTVolume patientCT = templateCT;
  for (int a = 0; a < 3; ++a)
  {
    patientCT.originMm[a] += shiftMm[a];
  }
  TemplateWarpJobOptions options;
  options.templateCTPath = (out / "template.mha").string();
  options.patientCTPath = (out / "patient.mha").string();
  writeCTVolume(templateCT, options.templateCTPath);
  writeCTVolume(patientCT, options.patientCTPath);
  // A sphere inside the phantom's airway, and a camera at its centre.
  const Eigen::Vector3d centre(32.0, 44.0, 19.0);
  const TriangleMesh sphere = fixtures::makeSphere(3.0, 2, centre);
  options.templateMeshPaths = { (out / "nose.vtp").string() };
  writePolyData(toPolyData(sphere), options.templateMeshPaths[0]);
  options.templatePosesPath = (out / "poses-in.json").string();
  const CameraPose camera =
    CameraPose::lookAt(centre, centre + Eigen::Vector3d(0.0, 1.0, 0.0), Eigen::Vector3d(0, 0, 1));
  writeFramePoses({ { 4, camera } }, options.templatePosesPath);
  options.outputFolder = (out / "warped").string();

  std::vector<std::string> shown;
  const TemplateWarpJobReport report = runTemplateWarpJob(
    options, ProgressCallback(), [&](const std::string& warning) { shown.push_back(warning); });
  EXPECT_EQ(shown, report.warnings);
  EXPECT_EQ(report.warnings, std::vector<std::string>());
  EXPECT_EQ(report.meshCount, 1u);
  EXPECT_EQ(report.poseCount, 1u);
  EXPECT_GT(report.registration.finalCorrelation, 0.9);
  const fs::path warped(options.outputFolder);
  const std::vector<std::string> expected = { (warped / "nose.vtp").string(),
    (warped / "poses.json").string(), (warped / "template-to-patient.nii.gz").string(),
    (warped / "patient-to-template.nii.gz").string() };
  EXPECT_EQ(report.outputPaths, expected);
  for (const std::string& path : expected)
  {
    EXPECT_TRUE(fs::is_regular_file(path)) << path;
  }
  std::ifstream json(warped / "registration.json");
  ASSERT_TRUE(json);
  EXPECT_EQ(nlohmann::json::parse(json), report.toJson());

  // The job carries the mesh and the pose by the field it reports and writes...
  const DisplacementField& field = report.registration.templateToPatient;
  const auto mapped = [&](const Eigen::Vector3d& x)
  {
    const std::array<double, 3> y = field.transformPoint({ x[0], x[1], x[2] });
    return Eigen::Vector3d(y[0], y[1], y[2]);
  };
  const TriangleMesh moved = toTriangleMesh(readPolyData(expected[0]));
  ASSERT_EQ(moved.numberOfVertices(), sphere.numberOfVertices());
  for (int v = 0; v < moved.numberOfVertices(); ++v)
  {
    ASSERT_LT((moved.vertices()[v] - mapped(sphere.vertices()[v])).norm(), 1e-4) << v;
  }
  const std::vector<FramePose> poses = readFramePoses(expected[1]);
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0].frameId, 4);
  EXPECT_LT((poses[0].cameraToWorld.centre - mapped(centre)).norm(), 1e-6);
  // And the registration finds the shift (SyN leaves up to about 0.9 mm
  // on this phantom, whose texture is all its mutual information has).
  for (int v = 0; v < moved.numberOfVertices(); ++v)
  {
    ASSERT_LT((moved.vertices()[v] - (sphere.vertices()[v] + shiftMm)).norm(), 1.5) << v;
  }
}

TEST(TemplateWarpJob, RefusesMeshesItCannotNameApartBeforeReadingAnything)
{
  const fs::path out = fixtures::freshTestFolder("template-warp-job");
  TemplateWarpJobOptions options;
  options.templateCTPath = (out / "no-such-template.mha").string();
  options.patientCTPath = (out / "no-such-patient.mha").string();
  options.outputFolder = (out / "never-made").string();
  options.templateMeshPaths = { "left/nose.vtp", "right/nose.stl" };
  EXPECT_EQ(
    jobError(options), "two template meshes would both be written as 'nose.vtp'; rename one");
  options.templateMeshPaths = { "notes.txt" };
  EXPECT_EQ(jobError(options),
    "'notes.txt': unsupported mesh type (expected .vtp, .vtk, .stl, .ply or .obj)");
  EXPECT_FALSE(fs::exists(options.outputFolder));
}
