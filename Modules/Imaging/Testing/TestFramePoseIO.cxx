#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/DisplacementFieldIO.h>
#include <vimlop/Imaging/FramePoseIO.h>

#include "ErrorMessage.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

using namespace vimlop;

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;

std::string write(const std::string& name, const std::string& text)
{
  const std::string path = out + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string poseError(const std::string& path)
{
  try
  {
    readFramePoses(path);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST(FramePoseIO, RoundTripsPosesAndIds)
{
  std::vector<FramePose> poses(3);
  for (int i = 0; i < 3; ++i)
  {
    poses[i].frameId = 10 * i + 1;
    poses[i].cameraToWorld.rotation = rotationFromVector(Eigen::Vector3d(0.1 * i, -0.2, 0.3));
    poses[i].cameraToWorld.centre = Eigen::Vector3d(100.0 + i, 80.5, -20.25 * i);
  }
  const std::string path = out + "/poses-roundtrip.json";
  writeFramePoses(poses, path);
  const std::vector<FramePose> back = readFramePoses(path);
  ASSERT_EQ(back.size(), 3u);
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_EQ(back[i].frameId, poses[i].frameId);
    EXPECT_LT((back[i].cameraToWorld.matrix() - poses[i].cameraToWorld.matrix()).norm(), 1e-12);
  }
}

TEST(FramePoseIO, ReadsTheDocumentedFormat)
{
  const std::string path = write("poses-documented.json",
    R"({"poses": [{"frame_id": 4, "camera_to_ct": [0, -1, 0, 10, 1, 0, 0, 20, 0, 0, 1, 30, 0, 0, 0, 1],
        "note": "ignored"}]})");
  const std::vector<FramePose> poses = readFramePoses(path);
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0].frameId, 4);
  // Row-major: the camera's x axis (first column) is CT +y.
  EXPECT_EQ(poses[0].cameraToWorld.rotation.col(0), Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(poses[0].cameraToWorld.centre, Eigen::Vector3d(10, 20, 30));
}

TEST(FramePoseIO, BadFilesGetOneLineErrors)
{
  EXPECT_EQ(
    poseError(out + "/no-poses-here.json"), "'" + out + "/no-poses-here.json': no such file");
  const std::string notJson = write("poses-not-json.json", "{ poses: ");
  EXPECT_EQ(poseError(notJson), "'" + notJson + "': not a JSON file");
  const std::string noArray = write("poses-no-array.json", R"({"frames": []})");
  EXPECT_EQ(poseError(noArray).rfind("'" + noArray + "': no \"poses\" array", 0), 0u);
  const std::string noId = write("poses-no-id.json", R"({"poses": [{"camera_to_ct": []}]})");
  EXPECT_EQ(poseError(noId), "'" + noId + "': pose 0 has no integer \"frame_id\"");
  const std::string shortMatrix =
    write("poses-short.json", R"({"poses": [{"frame_id": 1, "camera_to_ct": [1, 0, 0]}]})");
  EXPECT_EQ(poseError(shortMatrix),
    "'" + shortMatrix + "': pose 0: \"camera_to_ct\" must be 16 numbers (a 4x4 matrix, row-major)");
  const std::string scaled = write("poses-scaled.json",
    R"({"poses": [{"frame_id": 1, "camera_to_ct": [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1]}]})");
  EXPECT_EQ(poseError(scaled),
    "'" + scaled + "': pose 0: camera pose matrix: upper-left 3x3 block is not a rotation");
}

TEST(DisplacementFieldIO, RoundTripsAsVectorImages)
{
  DisplacementField field;
  field.dims = { 5, 4, 3 };
  field.spacingMm = { 0.9, 1.1, 2.0 };
  field.originMm = { -3.0, 7.5, 100.0 };
  field.direction = { 1, 0, 0, 0, -1, 0, 0, 0, 1 };
  field.displacements.resize(3 * field.numberOfPoints());
  for (std::size_t i = 0; i < field.displacements.size(); ++i)
  {
    field.displacements[i] = 0.25 * static_cast<double>(i % 17) - 2.0;
  }
  for (const std::string ext : { ".nii", ".nii.gz", ".mha", ".nrrd" })
  {
    const std::string path = out + "/field" + ext;
    writeDisplacementField(field, path);
    const DisplacementField back = readDisplacementField(path);
    EXPECT_EQ(back.dims, field.dims) << ext;
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(back.spacingMm[a], field.spacingMm[a], 1e-5) << ext;
      EXPECT_NEAR(back.originMm[a], field.originMm[a], 1e-4) << ext;
    }
    for (int i = 0; i < 9; ++i)
    {
      EXPECT_NEAR(back.direction[i], field.direction[i], 1e-6) << ext;
    }
    ASSERT_EQ(back.displacements.size(), field.displacements.size());
    for (std::size_t i = 0; i < field.displacements.size(); ++i)
    {
      ASSERT_FLOAT_EQ(
        static_cast<float>(back.displacements[i]), static_cast<float>(field.displacements[i]));
    }
  }
  EXPECT_THROW(writeDisplacementField(field, out + "/field.png"), Error);
  EXPECT_THROW(writeDisplacementField(DisplacementField(), out + "/empty.mha"), Error);
  EXPECT_THROW(readDisplacementField(out + "/no-field-here.mha"), Error);
}

namespace
{

DisplacementField smallField()
{
  DisplacementField field;
  field.dims = { 5, 4, 3 };
  field.displacements.assign(3 * field.numberOfPoints(), 0.5);
  return field;
}

std::string fieldError(const std::string& path)
{
  return fixtures::errorMessageOf([&] { readDisplacementField(path); });
}

} // namespace

TEST(DisplacementFieldIO, RefusesFieldsThatWouldMoveTheMeshAnywhereWithTheCause)
{
  DisplacementField notFinite = smallField();
  notFinite.displacements[3 * 7 + 1] = std::numeric_limits<double>::quiet_NaN();
  const std::string nan = out + "/field-nan.mha";
  writeDisplacementField(notFinite, nan);
  EXPECT_EQ(fieldError(nan), "'" + nan + "': grid point 7 holds a displacement that is not finite");

  DisplacementField sheared = smallField();
  sheared.direction = { 1, 0.5, 0, 0, 1, 0, 0, 0, 1 };
  const std::string shear = out + "/field-shear.nrrd";
  writeDisplacementField(sheared, shear);
  EXPECT_EQ(fieldError(shear),
    "'" + shear +
      "': the direction matrix is not orthonormal (its columns, the voxel axes, must be unit "
      "vectors at right angles)");

  // The CT reader's checks guard the field reader too.
  const std::string cut = out + "/field-cut.nii";
  writeDisplacementField(smallField(), cut);
  const auto bytes = std::filesystem::file_size(cut);
  std::filesystem::resize_file(cut, bytes - 12);
  EXPECT_EQ(fieldError(cut),
    "'" + cut + "': the file is truncated (" + std::to_string(bytes - 12) +
      " bytes, the header promises " + std::to_string(bytes) + ")");

  CTVolume scalar;
  scalar.dims = { 3, 3, 3 };
  scalar.intensities.assign(27, -1000.0f);
  const std::string ct = out + "/field-scalar.mha";
  writeCTVolume(scalar, ct);
  EXPECT_EQ(fieldError(ct),
    "'" + ct +
      "': the image has 1 components per voxel; a displacement field has 3 (its x, y and z in "
      "mm)");

  const std::string dicom = out + "/field.dcm";
  write("field.dcm", "not used");
  EXPECT_EQ(fieldError(dicom),
    "'" + dicom + "': unsupported field type (expected .nii, .nii.gz, .nrrd, .nhdr, .mha or .mhd)");
}
