#include <vimlop/Core/Error.h>
#include <vimlop/Video/FrameContoursIO.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

using namespace vimlop;

TEST(FrameContoursIO, WritesEachFramesPointsWithTheirNormals)
{
  ContourPoint p;
  p.pixel = { 10.5, 20.0 };
  p.normal = { 0.0, -1.0 };
  const std::string path =
    (std::filesystem::temp_directory_path() / "vimlop-test-frame-contours.json").string();
  writeFrameContours(
    { { "frame000.png", { p } }, { "frame001.png", {} } }, { 320, 240, true }, path);
  std::ifstream in(path);
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_EQ(json["format"], "vimlop-contours");
  EXPECT_EQ(json["version"], 1);
  ASSERT_EQ(json["frames"].size(), 2u);
  EXPECT_EQ(json["frames"][0]["name"], "frame000.png");
  EXPECT_EQ(json["frames"][0]["points"], nlohmann::json::parse("[[10.5, 20.0, 0.0, -1.0]]"));
  EXPECT_TRUE(json["frames"][1]["points"].empty());

  FrameContoursPictures pictures;
  const std::vector<FrameContours> back = readFrameContours(path, &pictures);
  EXPECT_EQ(pictures.widthPx, 320);
  EXPECT_EQ(pictures.heightPx, 240);
  EXPECT_TRUE(pictures.undistorted);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].name, "frame000.png");
  ASSERT_EQ(back[0].points.size(), 1u);
  EXPECT_EQ(back[0].points[0].pixel, p.pixel);
  EXPECT_EQ(back[0].points[0].normal, p.normal);
  EXPECT_TRUE(back[1].points.empty());
  std::filesystem::remove(path);
}

TEST(FrameContoursIO, RefusesFilesThatAreNotContoursWithTheirProblem)
{
  const std::string path =
    (std::filesystem::temp_directory_path() / "vimlop-test-bad-contours.json").string();
  const auto messageOf = [&](const std::string& text)
  {
    std::ofstream(path) << text;
    try
    {
      readFrameContours(path);
    }
    catch (const Error& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(messageOf("{not json"), "'" + path + "': not a JSON file");
  EXPECT_EQ(messageOf(R"({"format": "vimlop-sfm"})"),
    "'" + path +
      "': not a contours file of vimlop contours (its \"format\" is not \"vimlop-contours\")");
  EXPECT_EQ(
    messageOf(
      R"({"format": "vimlop-contours", "frames": [{"name": "a.png", "points": [[1, 2, 3]]}]})"),
    "'" + path + "': frame 'a.png': a point is not [u, v, nu, nv]");
  EXPECT_EQ(
    messageOf(
      R"({"format": "vimlop-contours", "frames": [{"name": "a.png", "points": [[1, 2, 3, 4]]}]})"),
    "'" + path +
      "': frame 'a.png': a point's pixel is not finite or its normal is not a unit vector");
  EXPECT_EQ(
    messageOf(R"({"format": "vimlop-contours"})").rfind("'" + path + "': malformed: ", 0), 0u);
  std::filesystem::remove(path);
}

TEST(FrameContoursIO, DrawsAPointAndItsNormalOnACopyOfTheFrame)
{
  const cv::Mat frame(32, 32, CV_8UC3, cv::Scalar(0, 0, 0));
  ContourPoint p;
  p.pixel = { 10.0, 10.0 };
  p.normal = { 1.0, 0.0 };
  const cv::Mat picture = drawFrameContours(frame, { p });
  EXPECT_EQ(cv::countNonZero(frame.reshape(1)), 0);
  EXPECT_GT(picture.at<cv::Vec3b>(10, 10)[1], 100); // the green dot
  EXPECT_GT(picture.at<cv::Vec3b>(10, 13)[0], 100); // the tick along +u
  EXPECT_EQ(picture.at<cv::Vec3b>(25, 25), cv::Vec3b(0, 0, 0));
}
