#include "ReportFixture.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Results/PerturbationRuns.h>
#include <vimlop/Results/RegistrationRecordIO.h>

#include "TestFolders.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace vimlop;

namespace
{

void expectMessage(const std::function<void()>& action, const std::string& expected)
{
  try
  {
    action();
    ADD_FAILURE() << "no error; expected: " << expected;
  }
  catch (const Error& e)
  {
    EXPECT_EQ(std::string(e.what()), expected);
  }
}

} // namespace

static std::string freshRecordWithoutConfidence()
{
  const std::string dir = fixtures::freshTestFolder("record-without-confidence").string();
  writeRegistrationRecord(fixtures::makeReportRecord(), dir);
  return dir;
}

TEST(RegistrationRecordIO, RoundTripsEverything)
{
  const RegistrationRecord record = fixtures::makeReportRecord();
  RegistrationRecord changed = record;
  changed.options.maxScale = 1.25; // finite and infinite bounds both survive
  changed.options.minScale = 0.8;
  changed.options.contourMatch.kappa = 150.0;
  changed.options.method = RegistrationMethod::IMLP;
  changed.confidence =
    RegistrationRecord::Confidence{ true, 6.5, "contour error 7.0 px", "canonical", 120, 17, 0.75 };
  changed.frameTimesS = { 0.0, 0.04, 0.12 };
  changed.versions["opencv"] = "4.6.0";
  changed.commandLine = "vimlop register --frames 'my frames' --ct ct.nrrd";
  changed.runWallS = 31.25;
  changed.framesWithoutPose = { { 4, "frame004.png", 0.16 }, { 9, "frame009.png" } };
  changed.frameSources.assign(changed.data.frames.size(), "");
  changed.frameSources.back() = "frame011.png";
  changed.inputs = { { "ct", "/data/ct", 123456789012ull, std::string(64, 'a') },
    { "intrinsics", "k.yaml", 42, std::string(64, 'b') } };
  changed.ctIdentity = { { "patient_id", "PHANTOM" }, { "series_instance_uid", "1.2.3" } };
  const std::string dir = fixtures::freshTestFolder("record-round-trip").string();
  writeRegistrationRecord(changed, dir);
  for (const char* file :
    { "result.json", "model.vtp", "sfm-points.vtp", "frame-table.vtt", "video-contours.vtp",
      "registered-points.vtp", "camera-poses.vtt", "correspondences.vtp", "targets.vtp" })
  {
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(dir) / file)) << file;
  }
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(dir) / "result.json.part"));

  const RegistrationRecord back = readRegistrationRecord(dir);
  EXPECT_EQ(back.source, record.source);
  EXPECT_EQ(back.frameSources, changed.frameSources);
  ASSERT_EQ(back.inputs.size(), 2u);
  EXPECT_EQ(back.inputs[0].role, "ct");
  EXPECT_EQ(back.inputs[0].path, "/data/ct");
  EXPECT_EQ(back.inputs[0].bytes, 123456789012ull);
  EXPECT_EQ(back.inputs[1].sha256, std::string(64, 'b'));
  EXPECT_EQ(back.ctIdentity, changed.ctIdentity);
  EXPECT_EQ(back.model.numberOfFaces(), record.model.numberOfFaces());
  EXPECT_LT((back.model.faceNormals()[7] - record.model.faceNormals()[7]).norm(), 1e-12);
  ASSERT_EQ(back.data.points.size(), record.data.points.size());
  EXPECT_LT((back.data.points[3] - record.data.points[3]).norm(), 1e-12);
  EXPECT_LT((back.data.pointCovariances[3] - record.data.pointCovariances[3]).norm(), 1e-15);
  ASSERT_EQ(back.data.frames.size(), record.data.frames.size());
  for (size_t j = 0; j < record.data.frames.size(); ++j)
  {
    const VideoFrame& a = record.data.frames[j];
    const VideoFrame& b = back.data.frames[j];
    EXPECT_EQ(a.frameId, b.frameId);
    EXPECT_EQ(a.intrinsics.widthPx, b.intrinsics.widthPx);
    EXPECT_DOUBLE_EQ(a.intrinsics.cx, b.intrinsics.cx);
    EXPECT_LT((a.cameraToSfm.matrix() - b.cameraToSfm.matrix()).norm(), 1e-12);
    ASSERT_EQ(a.contour.size(), b.contour.size());
    EXPECT_LT((a.contour.back().pixel - b.contour.back().pixel).norm(), 1e-12);
    EXPECT_LT((a.contour.back().normal - b.contour.back().normal).norm(), 1e-12);
  }
  EXPECT_EQ(back.options.method, RegistrationMethod::IMLP);
  EXPECT_DOUBLE_EQ(back.options.maxScale, 1.25);
  EXPECT_DOUBLE_EQ(back.options.contourMatch.kappa, 150.0);
  EXPECT_NEAR(
    back.options.contourMatch.maxAngleDeg, record.options.contourMatch.maxAngleDeg, 1e-12);
  EXPECT_LT((back.initialSfmToCT.matrix() - record.initialSfmToCT.matrix()).norm(), 1e-12);

  const RegistrationResult& a = record.result;
  const RegistrationResult& b = back.result;
  EXPECT_LT((a.sfmToCT.matrix() - b.sfmToCT.matrix()).norm(), 1e-12);
  EXPECT_EQ(b.termination, TerminationReason::Converged);
  EXPECT_EQ(b.iterations, 8);
  ASSERT_EQ(b.history.size(), a.history.size());
  EXPECT_EQ(b.history[4].withContours, true);
  EXPECT_DOUBLE_EQ(b.history[4].cost, a.history[4].cost);
  EXPECT_DOUBLE_EQ(b.history[4].contourErrorPx, a.history[4].contourErrorPx);
  EXPECT_LT((b.history[4].transform.matrix() - a.history[4].transform.matrix()).norm(), 1e-12);
  EXPECT_EQ(b.pointInliers, a.pointInliers);
  EXPECT_LT((b.pointMatches[9] - a.pointMatches[9]).norm(), 1e-12);
  ASSERT_EQ(b.frames.size(), a.frames.size());
  EXPECT_EQ(b.frames[1].inliers, a.frames[1].inliers);
  EXPECT_LT((b.frames[1].cameraToCT.matrix() - a.frames[1].cameraToCT.matrix()).norm(), 1e-12);
  ASSERT_EQ(b.frames[1].correspondences.size(), 3u);
  EXPECT_FALSE(b.frames[1].correspondences[1].inlier);
  EXPECT_LT(
    (b.frames[1].correspondences[2].modelPixel - a.frames[1].correspondences[2].modelPixel).norm(),
    1e-12);
  ASSERT_TRUE(back.truth.has_value());
  EXPECT_EQ(back.truth->targetsCT.size(), record.truth->targetsCT.size());
  EXPECT_EQ(back.truth->camerasCT.size(), record.truth->camerasCT.size());
  EXPECT_EQ(back.frameImages, std::vector<std::string>(3, std::string()));
  ASSERT_TRUE(back.confidence.has_value());
  EXPECT_TRUE(back.confidence->failure);
  EXPECT_DOUBLE_EQ(back.confidence->failureThresholdPx, 6.5);
  EXPECT_DOUBLE_EQ(back.confidence->failureResidualMm, 0.75);
  EXPECT_EQ(back.confidence->reason, "contour error 7.0 px");
  EXPECT_EQ(back.frameTimesS, changed.frameTimesS);
  EXPECT_EQ(back.confidence->init, "canonical");
  EXPECT_EQ(back.confidence->candidates, 120);
  EXPECT_EQ(back.confidence->winner, 17);
  EXPECT_EQ(back.versions.at("opencv"), "4.6.0");
  EXPECT_EQ(back.commandLine, changed.commandLine);
  EXPECT_DOUBLE_EQ(back.runWallS, 31.25);
  ASSERT_EQ(back.framesWithoutPose.size(), 2u);
  EXPECT_EQ(back.framesWithoutPose[0].frameId, 4);
  EXPECT_EQ(back.framesWithoutPose[0].source, "frame004.png");
  EXPECT_DOUBLE_EQ(back.framesWithoutPose[0].timeS, 0.16);
  EXPECT_TRUE(std::isnan(back.framesWithoutPose[1].timeS));
  EXPECT_FALSE(readRegistrationRecord(freshRecordWithoutConfidence()).confidence.has_value());
}

TEST(RegistrationRecordIO, FrameTimesAreOnEveryFrameOrNone)
{
  RegistrationRecord record = fixtures::makeReportRecord();
  ASSERT_EQ(record.data.frames.size(), 3u);
  const std::string dir = fixtures::freshTestFolder("record-frame-times").string();
  record.frameTimesS = { 0.0, 0.5 };
  expectMessage([&] { writeRegistrationRecord(record, dir); },
    "a registration record with 2 frame times for 3 frames: one per frame or none");
  EXPECT_TRUE(readRegistrationRecord(freshRecordWithoutConfidence()).frameTimesS.empty());

  record.frameTimesS = { 0.0, 0.5, 1.0 };
  writeRegistrationRecord(record, dir);
  const std::string path = dir + "/result.json";
  std::string text;
  {
    std::ifstream in(path);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const auto lastTime = text.rfind("\"time_s\"");
  ASSERT_NE(lastTime, std::string::npos);
  std::ofstream(path) << text.substr(0, lastTime) + "\"time_x\"" + text.substr(lastTime + 8);
  expectMessage([&] { readRegistrationRecord(dir); },
    "'" + dir + "': result.json gives time_s for 2 of its 3 frames: on every frame or on none");
  std::ofstream(path) << text.substr(0, lastTime) + "\"time_s\": \"soon\", \"time_x\"" +
      text.substr(lastTime + 8);
  expectMessage([&] { readRegistrationRecord(dir); },
    "'" + dir + "': frame 2's time_s is not a finite number of seconds");
}

TEST(RegistrationRecordIO, FramePicturesAreNamedByTheirFrameIds)
{
  EXPECT_EQ(resultFrameImageName(11), "frames/frame-0011.png");
  EXPECT_EQ(resultFrameImageName(123456), "frames/frame-123456.png");
}

TEST(RegistrationRecordIO, ReportsFoldersThatAreNotResults)
{
  expectMessage(
    [] { readRegistrationRecord("no-such-folder"); }, "'no-such-folder': no such folder");
  const std::string empty = fixtures::freshTestFolder("record-empty").string();
  std::filesystem::create_directories(empty);
  expectMessage([&] { readRegistrationRecord(empty); },
    "'" + empty + "': not a VIMLOP result folder (no result.json)");

  const std::string other = fixtures::freshTestFolder("record-other").string();
  std::filesystem::create_directories(other);
  std::ofstream(other + "/result.json") << "{\"format\": \"something-else\"}\n";
  expectMessage([&] { readRegistrationRecord(other); },
    "'" + other + "/result.json': not a VIMLOP result (format is not 'vimlop-result')");

  std::ofstream(other + "/result.json") << "{\"format\": \"vimlop-result\", \"version\": 99}\n";
  expectMessage([&] { readRegistrationRecord(other); },
    "'" + other + "/result.json': format version 99 is newer than this program reads (1)");

  // A result folder that lost a file names the file.
  const std::string partial = fixtures::freshTestFolder("record-partial").string();
  writeRegistrationRecord(fixtures::makeReportRecord(), partial);
  std::filesystem::remove(partial + "/registered-points.vtp");
  expectMessage([&] { readRegistrationRecord(partial); },
    "'" + partial + "/registered-points.vtp': no such file");
}

TEST(PerturbationRuns, RoundTripAndBadInput)
{
  const std::string dir = fixtures::freshTestFolder("perturbation-runs").string();
  std::filesystem::create_directories(dir);
  const std::vector<PerturbationRun> runs = { { 2.0, 2.0, 0.3, 1.1, true },
    { 8.0, 8.0, 6.5, 9.0, false } };
  writePerturbationRuns(runs, dir + "/runs.json");
  const std::vector<PerturbationRun> back = readPerturbationRuns(dir + "/runs.json");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_DOUBLE_EQ(back[1].finalErrorMm, 6.5);
  EXPECT_FALSE(back[1].success);
  std::ofstream(dir + "/bad.json") << "{\"runs\": [{\"offset_mm\": 1}]}\n";
  expectMessage([&] { readPerturbationRuns(dir + "/bad.json"); },
    "'" + dir + "/bad.json': run 0 needs numbers offset_mm, final_error_mm and contour_error_px");
  std::ofstream(dir + "/none.json") << "{\"offsets\": []}\n";
  expectMessage([&] { readPerturbationRuns(dir + "/none.json"); },
    "'" + dir + "/none.json': no \"runs\" list (a perturbation study lists its runs)");
}
