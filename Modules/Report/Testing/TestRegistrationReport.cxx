// The report's pictures against baseline images (VTK's image comparison,
// vtkImageDifference), and a proof that the comparison catches a wrong overlay.
//
// Baselines live in Testing/Data/Baseline. When a picture changes on
// purpose, run the test with VIMLOP_UPDATE_BASELINES=1 in the environment:
// it then writes the new pictures there (check them before committing).

#include "ErrorMessage.h"
#include "ReportFixture.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/CTVolume.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Rendering/ContourOverlay.h>
#include <vimlop/Rendering/PNGImageIO.h>
#include <vimlop/Rendering/vtkVIMLOPSilhouetteRenderer.h>
#include <vimlop/Report/RegisteredVideo.h>
#include <vimlop/Report/RegistrationReport.h>
#include <vimlop/Results/RegistrationRecordIO.h>

#include "TestFolders.h"

#include <gtest/gtest.h>

#include <vtkImageData.h>
#include <vtkImageDifference.h>
#include <vtkNew.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace vimlop;

namespace
{

namespace fs = std::filesystem;

/**
 * The comparison: VTK's vtkImageDifference without its allowances for
 * rendering differences between machines (a shift of up to two pixels and
 * 3 x 3 averaging), which forgive a one-pixel contour line moved by three
 * pixels entirely. A pixel counts when its colour differs by more than
 * `pixelThreshold` (sum over R, G, B); the picture fails when the thresholded
 * error exceeds `maxError`. Identical renderings (Mesa llvmpipe, no
 * anti-aliasing) give 0; the model contours of one overlay moved by one pixel
 * give about 170, by three pixels about 240.
 */
constexpr int pixelThreshold = 16;
constexpr double maxError = 25.0;

struct Comparison
{
  bool passed = false;
  double error = 0.0;
  std::string log;
};

Comparison compareWithBaseline(vtkImageData* image, const std::string& name)
{
  const std::string baseline = std::string(VIMLOP_TEST_DATA_DIR) + "/Baseline/" + name;
  const char* update = std::getenv("VIMLOP_UPDATE_BASELINES");
  if (update && std::strcmp(update, "1") == 0)
  {
    writePNG(image, baseline);
  }
  Comparison c;
  vtkSmartPointer<vtkImageData> expected;
  try
  {
    expected = readPNG(baseline);
  }
  catch (const Error& e)
  {
    c.log = e.what();
    return c;
  }
  int a[3], b[3];
  image->GetDimensions(a);
  expected->GetDimensions(b);
  if (a[0] != b[0] || a[1] != b[1])
  {
    c.log = "the picture is " + std::to_string(a[0]) + " x " + std::to_string(a[1]) +
      " pixels, the baseline " + std::to_string(b[0]) + " x " + std::to_string(b[1]);
    return c;
  }
  vtkNew<vtkImageDifference> difference;
  difference->SetInputData(image);
  difference->SetImageData(expected);
  difference->AllowShiftOff();
  difference->AveragingOff();
  difference->SetThreshold(pixelThreshold);
  difference->Update();
  c.error = difference->GetThresholdedError();
  c.passed = c.error <= maxError;
  if (!c.passed)
  {
    // What was drawn and where it differs, for a look.
    const std::string stem =
      std::string(VIMLOP_TEST_OUTPUT_DIR) + "/" + name.substr(0, name.size() - 4);
    writePNG(image, stem + "-test.png");
    writePNG(difference->GetOutput(), stem + "-difference.png");
    c.log = "thresholded error " + std::to_string(c.error) + " > " + std::to_string(maxError) +
      "; see " + stem + "-test.png and -difference.png";
  }
  return c;
}

Comparison compareFileWithBaseline(const std::string& path, const std::string& name)
{
  return compareWithBaseline(readPNG(path), name);
}

std::vector<PerturbationRun> makeRuns()
{
  // Offsets 0..10 mm, three runs each; errors grow with the offset and the
  // last offsets fail, with a contour error that says so.
  std::vector<PerturbationRun> runs;
  for (int offset = 0; offset <= 10; offset += 2)
  {
    for (int k = 0; k < 3; ++k)
    {
      PerturbationRun run;
      run.offsetMm = offset;
      run.offsetDeg = offset;
      run.success = offset < 8 || (offset == 8 && k == 0);
      run.finalErrorMm = run.success ? 0.2 + 0.03 * offset + 0.05 * k : 3.0 + 0.4 * offset + k;
      run.contourErrorPx = run.success ? 1.0 + 0.1 * k + 0.02 * offset : 6.0 + 0.5 * offset + k;
      runs.push_back(run);
    }
  }
  return runs;
}

RegistrationReportOptions smallPictures()
{
  RegistrationReportOptions options;
  options.sceneWidthPx = 320;
  options.sceneHeightPx = 240;
  options.chartWidthPx = 320;
  options.chartHeightPx = 240;
  options.maxOverlayFrames = 1;
  return options;
}

} // namespace

TEST(RegistrationReport, WritesEveryPictureAsInTheBaselines)
{
  const std::string result = fixtures::freshTestFolder("report-fixture-result").string();
  writeRegistrationRecord(fixtures::makeReportRecord(result), result);
  const RegistrationRecord record = readRegistrationRecord(result);
  const std::string out = fixtures::freshTestFolder("report-fixture").string();
  const RegistrationReport report =
    RegistrationReport::write(&record, result, makeRuns(), out, smallPictures());

  // Numbers: the made-up result is better than its start, as it should be.
  ASSERT_EQ(report.frames.size(), 3u);
  EXPECT_LT(report.contourErrorAfterPx, 0.5 * report.contourErrorBeforePx);
  ASSERT_TRUE(report.treAfterMm.has_value());
  EXPECT_LT(*report.treAfterMm, 0.3);
  EXPECT_GT(*report.treBeforeMm, 1.0);
  EXPECT_FALSE(report.frames[0].overlay.empty());
  EXPECT_TRUE(report.frames[1].overlay.empty()); // one overlay asked for
  ASSERT_TRUE(report.frames[0].cameraPositionErrorMm.has_value());

  // Files.
  for (const char* file : { "index.html", "report.json", "scene.png", "frames.png",
         "iterations.png", "perturbation.png" })
  {
    EXPECT_TRUE(fs::exists(fs::path(out) / file)) << file;
  }
  nlohmann::json j;
  std::ifstream(fs::path(out) / "report.json") >> j;
  EXPECT_EQ(j.at("format"), "vimlop-report");
  EXPECT_EQ(j.at("frames").size(), 3u);
  EXPECT_NEAR(j.at("registration").at("tre_after_mm").get<double>(), *report.treAfterMm, 1e-12);
  EXPECT_EQ(j.at("perturbation").at("offsets").size(), 6u);
  EXPECT_DOUBLE_EQ(
    j.at("perturbation").at("offsets")[4].at("success_rate").get<double>(), 1.0 / 3.0);
  EXPECT_EQ(j.at("parameters").at("method"), "vimlop");
  std::stringstream html;
  html << std::ifstream(fs::path(out) / "index.html").rdbuf();
  for (const std::string& picture : report.pictures)
  {
    EXPECT_NE(html.str().find("src=\"" + picture + "\""), std::string::npos) << picture;
  }
  EXPECT_NE(html.str().find("TRE before / after (mm)"), std::string::npos);
  EXPECT_NE(html.str().find("contour_kappa"), std::string::npos);

  // Pictures.
  const std::pair<std::string, std::string> pictures[] = {
    { report.frames[0].overlay, "report-overlay.png" }, { "scene.png", "report-scene.png" },
    { "frames.png", "report-frames.png" }, { "iterations.png", "report-iterations.png" },
    { "perturbation.png", "report-perturbation.png" }
  };
  for (const auto& [file, baseline] : pictures)
  {
    const Comparison c = compareFileWithBaseline((fs::path(out) / file).string(), baseline);
    EXPECT_TRUE(c.passed) << file << " differs from " << baseline << " (error " << c.error << "):\n"
                          << c.log;
  }
}

TEST(RegistrationReport, AReportOnTheCallersModelHasTheNumbersOfOneThatBuildsItsOwn)
{
  const std::string result = fixtures::freshTestFolder("report-model-result").string();
  const RegistrationRecord record = fixtures::makeReportRecord(result);
  RegistrationReportOptions options = smallPictures();
  options.maxOverlayFrames = 1;
  const RegistrationReport own = RegistrationReport::write(
    &record, result, {}, fixtures::freshTestFolder("report-own-model").string(), options);
  const RegistrationModel model = makeEmbreeRegistrationModel(record.model);
  const RegistrationReport given = RegistrationReport::write(
    &record, result, {}, fixtures::freshTestFolder("report-given-model").string(), options, &model);
  ASSERT_EQ(given.frames.size(), own.frames.size());
  for (size_t j = 0; j < own.frames.size(); ++j)
  {
    EXPECT_DOUBLE_EQ(given.frames[j].contourErrorBeforePx, own.frames[j].contourErrorBeforePx);
    EXPECT_DOUBLE_EQ(given.frames[j].contourErrorAfterPx, own.frames[j].contourErrorAfterPx);
    EXPECT_EQ(given.frames[j].matchedAfter, own.frames[j].matchedAfter);
  }
  EXPECT_GT(given.frames.front().matchedAfter, 0);
}

TEST(RegistrationReport, TheBaselineComparisonFailsOnAShiftedOverlay)
{
  // The overlay of the first test, composed again: as is it passes; with the
  // model contours of the right half moved 3 pixels it must fail.
  const std::string result = fixtures::freshTestFolder("report-shift-result").string();
  const RegistrationRecord record = fixtures::makeReportRecord(result);
  const VideoFrame& frame = record.data.frames.front();
  vtkSmartPointer<vtkImageData> picture = readPNG(result + "/" + record.frameImages.front());
  vtkNew<vtkVIMLOPSilhouetteRenderer> silhouettes;
  silhouettes->SetMesh(record.model);
  const int w = frame.intrinsics.widthPx;
  const int h = frame.intrinsics.heightPx;
  const auto before =
    silhouettes->RenderContours(frame.intrinsics, record.initialSfmToCT.apply(frame.cameraToSfm));
  const auto after =
    silhouettes->RenderContours(frame.intrinsics, record.result.frames[0].cameraToCT);
  const auto left = composeContourOverlay(w, h, picture, before, frame.contour);

  const Comparison same = compareWithBaseline(
    placeSideBySide({ left, composeContourOverlay(w, h, picture, after, frame.contour) }, 4),
    "report-overlay.png");
  EXPECT_TRUE(same.passed) << same.log;

  auto shifted = vtkSmartPointer<vtkImageData>::New();
  shifted->DeepCopy(after);
  auto* in = static_cast<unsigned char*>(after->GetScalarPointer());
  auto* out = static_cast<unsigned char*>(shifted->GetScalarPointer());
  std::memset(out, 0, static_cast<size_t>(w) * h);
  const int shiftPx = 3;
  for (int row = 0; row < h; ++row)
  {
    for (int u = 0; u + shiftPx < w; ++u)
    {
      out[row * w + u + shiftPx] = in[row * w + u];
    }
  }
  const auto wrongImage =
    placeSideBySide({ left, composeContourOverlay(w, h, picture, shifted, frame.contour) }, 4);
  const Comparison wrong = compareWithBaseline(wrongImage, "report-overlay.png");
  std::cout << "overlay vs baseline: error " << same.error << " as is, " << wrong.error
            << " with the contours shifted by " << shiftPx << " px (limit " << maxError << ")\n";
  EXPECT_FALSE(wrong.passed) << wrong.log;
}

TEST(RegistrationReport, ReportsNothingToReport)
{
  try
  {
    RegistrationReport::write(
      nullptr, "", {}, fixtures::freshTestFolder("report-nothing").string(), {});
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(
      e.what(), "report: nothing to report (no registration result and no perturbation runs)");
  }
}

namespace
{

/// The colour of the picture at (u, row from the top), RGB.
std::array<int, 3> colourAt(vtkImageData* picture, int u, int rowFromTop)
{
  int dims[3];
  picture->GetDimensions(dims);
  const auto* p =
    static_cast<const unsigned char*>(picture->GetScalarPointer(u, dims[1] - 1 - rowFromTop, 0));
  return { p[0], p[1], p[2] };
}

/// Report and registered video of the fixture's record with the given failure check.
nlohmann::json reportAndVideoOf(const std::optional<RegistrationRecord::Confidence>& confidence,
  const std::string& name, std::string& html, vtkSmartPointer<vtkImageData>& videoFrame)
{
  const std::string result = fixtures::freshTestFolder(name).string();
  RegistrationRecord record = fixtures::makeReportRecord(result);
  record.confidence = confidence;
  record.commandLine = "vimlop register --frames 'my frames' --ct ct.nrrd";
  record.runWallS = 12.5;
  record.inputs = { { "intrinsics", "k.yaml", 42, std::string(64, 'b') } };
  const std::string out = (fs::path(result) / "report").string();
  RegistrationReport::write(&record, result, {}, out, smallPictures());
  const std::vector<std::string> written = writeRegisteredVideo(record, result, 10.0);
  EXPECT_EQ(written.back(), "registered-video.avi");
  videoFrame = readPNG((fs::path(result) / written.front()).string());
  std::stringstream text;
  text << std::ifstream(fs::path(out) / "index.html").rdbuf();
  html = text.str();
  nlohmann::json j;
  std::ifstream(fs::path(out) / "report.json") >> j;
  return j;
}

} // namespace

TEST(RegistrationReport, AFlaggedResultSaysSoAtTheTopOfThePageInTheJsonAndOnEveryVideoFrame)
{
  std::string html;
  vtkSmartPointer<vtkImageData> frame;
  const nlohmann::json j = reportAndVideoOf(
    RegistrationRecord::Confidence{ true, 1.0,
      "the contour error 1.20 px is above the threshold of 1.00 px", "canonical", 12, 3 },
    "report-flagged", html, frame);
  EXPECT_EQ(j.at("verdict").at("status"), "flagged");
  EXPECT_DOUBLE_EQ(j.at("verdict").at("threshold_px").get<double>(), 1.0);
  const std::string headline = "FLAGGED AS A FAILURE, do not navigate: the contour error 1.20 px "
                               "is above the threshold of 1.00 px";
  EXPECT_EQ(j.at("verdict").at("headline"), headline);
  // The banner comes before anything else in the body.
  const size_t banner = html.find("<div id=\"verdict\" class=\"verdict flagged\">" + headline);
  ASSERT_NE(banner, std::string::npos) << html.substr(0, 2000);
  EXPECT_LT(banner, html.find("<h2>"));
  // The video's band is red; below it is the picture, not the band.
  const std::array<int, 3> red = { 179, 22, 27 };
  EXPECT_EQ(colourAt(frame, 2, 2), red);
  EXPECT_NE(colourAt(frame, 2, 40), red);
}

TEST(RegistrationReport, AResultThatPassedItsCheckIsShownRegisteredAndTheRunIsRecorded)
{
  std::string html;
  vtkSmartPointer<vtkImageData> frame;
  const nlohmann::json j =
    reportAndVideoOf(RegistrationRecord::Confidence{ false, 3.0, "", "canonical", 12, 3 },
      "report-registered", html, frame);
  EXPECT_EQ(j.at("verdict").at("status"), "registered");
  EXPECT_NE(html.find("class=\"verdict registered\">REGISTERED: contour error 1.20 px (flagged "
                      "above 3.00 px)"),
    std::string::npos);
  EXPECT_EQ(colourAt(frame, 2, 2), (std::array<int, 3>{ 27, 122, 46 }));
  // The run: command line, the whole run's time (not the winning start's), inputs, versions.
  const nlohmann::json& run = j.at("run");
  EXPECT_EQ(run.at("command_line"), "vimlop register --frames 'my frames' --ct ct.nrrd");
  EXPECT_DOUBLE_EQ(run.at("run_wall_s").get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(run.at("registration_runtime_s").get<double>(), 0.5);
  EXPECT_TRUE(run.at("versions").contains("vimlop"));
  EXPECT_EQ(run.at("inputs")[0].at("path"), "k.yaml");
  EXPECT_NE(
    html.find("<pre>vimlop register --frames 'my frames' --ct ct.nrrd</pre>"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>run time until the result (s)</td><td>12.5 "), std::string::npos);
  EXPECT_NE(html.find("src=\"frames.png\""), std::string::npos);
}

TEST(RegistrationReport, AResultWithoutAFailureCheckIsNotCalledRegistered)
{
  std::string html;
  vtkSmartPointer<vtkImageData> frame;
  const nlohmann::json j = reportAndVideoOf(std::nullopt, "report-unchecked", html, frame);
  EXPECT_EQ(j.at("verdict").at("status"), "unchecked");
  EXPECT_EQ(html.find("REGISTERED"), std::string::npos);
  EXPECT_NE(html.find("class=\"verdict unchecked\">NOT CHECKED"), std::string::npos);
  EXPECT_TRUE(j.at("run").at("run_wall_s").is_number());
}

namespace
{

/// Bone (1000 HU) with three balls of air around `centre`: 20 mm to the
/// patient's left (radius 15), superior (radius 10) and anterior (radius 8).
CTVolume boneWithAirAround(const Eigen::Vector3d& centre)
{
  CTVolume ct;
  ct.dims = { 121, 121, 121 };
  ct.originMm = { centre.x() - 60.0, centre.y() - 60.0, centre.z() - 60.0 };
  ct.intensities.assign(ct.numberOfVoxels(), 1000.0f);
  const std::pair<Eigen::Vector3d, double> balls[] = { { centre + 20.0 * Eigen::Vector3d::UnitX(),
                                                         15.0 },
    { centre + 20.0 * Eigen::Vector3d::UnitZ(), 10.0 },
    { centre - 20.0 * Eigen::Vector3d::UnitY(), 8.0 } };
  for (int k = 0; k < 121; ++k)
  {
    for (int j = 0; j < 121; ++j)
    {
      for (int i = 0; i < 121; ++i)
      {
        const std::array<double, 3> p = ct.indexToPhysical({ double(i), double(j), double(k) });
        for (const auto& [ball, radius] : balls)
        {
          if ((Eigen::Vector3d(p[0], p[1], p[2]) - ball).norm() < radius)
          {
            ct.intensities[i + 121 * (j + 121 * static_cast<size_t>(k))] = -1000.0f;
          }
        }
      }
    }
  }
  return ct;
}

} // namespace

TEST(RegistrationReport, TheCTSlicesShowTheScopeWhereItIsInRadiologicalOrientation)
{
  const std::string result = fixtures::freshTestFolder("report-ct-slices").string();
  const RegistrationRecord record = fixtures::makeReportRecord(result);
  // The middle frame's camera is the one drawn, at the slices' centres.
  const Eigen::Vector3d scope = record.result.frames[1].cameraToCT.centre;
  const std::string ctPath = result + "/ct.nrrd";
  writeCTVolume(boneWithAirAround(scope), ctPath);
  RegistrationReportOptions options = smallPictures();
  options.ctPath = ctPath;
  const std::string out = result + "/report";
  const RegistrationReport report = RegistrationReport::write(&record, result, {}, out, options);
  EXPECT_NE(std::find(report.pictures.begin(), report.pictures.end(), "ct-slices.png"),
    report.pictures.end());
  const vtkSmartPointer<vtkImageData> slices = readPNG(out + "/ct-slices.png");
  int dims[3];
  slices->GetDimensions(dims);
  ASSERT_EQ(dims[0], 3 * 256 + 8);
  ASSERT_EQ(dims[1], 256);
  // 20 mm from the centre is 43 px (256 px over 120 mm).
  const auto grey = [&](int panel, int u, int v)
  { return colourAt(slices, panel * 260 + u, v)[0]; };
  const int near = 128 - 43, far = 128 + 43;
  // Axial: the patient's left on the right, anterior up.
  EXPECT_LT(grey(0, far, 128), 60);
  EXPECT_GT(grey(0, near, 128), 150);
  EXPECT_LT(grey(0, 128, near), 60);
  EXPECT_GT(grey(0, 128, far), 150);
  // Coronal: the patient's left on the right, superior up.
  EXPECT_LT(grey(1, far, 128), 60);
  EXPECT_GT(grey(1, near, 128), 150);
  EXPECT_LT(grey(1, 128, near), 60);
  EXPECT_GT(grey(1, 128, far), 150);
  // Sagittal: anterior on the left, superior up.
  EXPECT_LT(grey(2, near, 128), 60);
  EXPECT_GT(grey(2, far, 128), 150);
  EXPECT_LT(grey(2, 128, near), 60);
  EXPECT_GT(grey(2, 128, far), 150);
  // The scope's ring at the centre of every slice.
  for (int panel = 0; panel < 3; ++panel)
  {
    int yellow = 0;
    for (int v = 120; v <= 136; ++v)
    {
      for (int u = 120; u <= 136; ++u)
      {
        const std::array<int, 3> c = colourAt(slices, panel * 260 + u, v);
        yellow += c[0] > 180 && c[1] > 150 && c[2] < 90;
      }
    }
    EXPECT_GT(yellow, 15) << "panel " << panel;
  }
  std::stringstream html;
  html << std::ifstream(out + "/index.html").rdbuf();
  EXPECT_NE(html.str().find("<img src=\"ct-slices.png\""), std::string::npos);
}

TEST(RegistrationReport, ACTThatCannotBeReadIsAnErrorWhenGivenAndANoteWhenOnlyRecorded)
{
  const std::string result = fixtures::freshTestFolder("report-ct-unreadable").string();
  RegistrationRecord record = fixtures::makeReportRecord(result);
  const std::string bad = result + "/ct.nrrd";
  std::ofstream(bad) << "not a CT\n";
  RegistrationReportOptions options = smallPictures();
  options.ctPath = bad;
  const std::string message = fixtures::errorMessageOf(
    [&] { RegistrationReport::write(&record, result, {}, result + "/report-given", options); });
  EXPECT_NE(message.find("ct.nrrd"), std::string::npos) << message;

  // Recorded as the run's CT: the report is written all the same, and says why there are no slices.
  record.inputs = { { "ct", bad, 9, std::string(64, 'c') } };
  const RegistrationReport report =
    RegistrationReport::write(&record, result, {}, result + "/report-recorded", smallPictures());
  EXPECT_EQ(std::find(report.pictures.begin(), report.pictures.end(), "ct-slices.png"),
    report.pictures.end());
  std::stringstream html;
  html << std::ifstream(result + "/report-recorded/index.html").rdbuf();
  EXPECT_NE(
    html.str().find("<p>Not drawn: the recorded CT could not be read ("), std::string::npos);
}
