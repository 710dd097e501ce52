#include <vimlop/Core/Error.h>
#include <vimlop/Pipeline/RegistrationOutputs.h>
#include <vimlop/Pipeline/VideoRegistrationInputs.h>

#include <gtest/gtest.h>

namespace vimlop
{
namespace
{

std::string startError(const std::string& text)
{
  try
  {
    VideoRegistrationInputs().setStart(text, "--init");
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

TEST(VideoRegistrationInputs, TakeTheStartFromItsTextForm)
{
  VideoRegistrationInputs inputs;
  inputs.setStart("manual:pose.json", "--init");
  EXPECT_EQ(inputs.startMode, StartMode::Manual);
  EXPECT_EQ(inputs.startPosesPath, "pose.json");
  inputs.setStart("canonical", "--init");
  EXPECT_EQ(inputs.startMode, StartMode::Canonical);
  EXPECT_EQ(inputs.startPosesPath, "");
  inputs.setStart("canonical:warped.json", "--init");
  EXPECT_EQ(inputs.startPosesPath, "warped.json");
  EXPECT_EQ(startError("manual:"),
    "--init: expected manual:POSE.json, canonical or canonical:POSES.json, got 'manual:'");
  EXPECT_EQ(startError("canonically"),
    "--init: expected manual:POSE.json, canonical or canonical:POSES.json, got 'canonically'");
}

TEST(VideoRegistrationInputs, TakeTheStructureFromMotionFromItsTextForm)
{
  VideoRegistrationInputs inputs;
  inputs.setStructureFromMotion("colmap:sparse/0", "--sfm");
  EXPECT_EQ(inputs.colmapFolder, "sparse/0");
  inputs.setStructureFromMotion("builtin", "--sfm");
  EXPECT_EQ(inputs.colmapFolder, "");
  EXPECT_THROW(inputs.setStructureFromMotion("colmap:", "--sfm"), Error);
}

TEST(RegistrationSummaryLines, SayTheFlagAndTheTruthErrorsWhenThereAreSome)
{
  nlohmann::json summary = { { "frames", 8 }, { "points", 900 }, { "init", "manual" },
    { "candidates", 1 }, { "runtime_s", 2.5 }, { "scale", 0.5 }, { "residual_error_mm", 0.2 },
    { "contour_error_px", 7.5 }, { "failure", true },
    { "failure_reason", "the contour error 7.50 px is above the threshold of 6.00 px" } };
  std::vector<std::string> lines = registrationSummaryLines(summary);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0],
    "registered 8 frames (900 SfM points) from manual (1 candidates) in 2.5 s: scale 0.5000 "
    "mm/unit, residual 0.200 mm, contour error 7.50 px -- FLAGGED AS A FAILURE: the contour "
    "error 7.50 px is above the threshold of 6.00 px");
  summary["failure"] = false;
  summary["camera_position_error_mm"] = { { "mean", 0.1 }, { "max", 0.3 } };
  summary["camera_angle_error_deg"] = { { "mean", 0.2 }, { "max", 0.4 } };
  lines = registrationSummaryLines(summary);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].find("FLAGGED"), std::string::npos);
  EXPECT_EQ(
    lines[1], "camera error against the truth: 0.100 mm (max 0.300), 0.200 deg (max 0.400)");
}

} // namespace
} // namespace vimlop
