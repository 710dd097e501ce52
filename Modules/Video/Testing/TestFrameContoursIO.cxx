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
  writeFrameContours({ { "frame000.png", { p } }, { "frame001.png", {} } }, path);
  std::ifstream in(path);
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_EQ(json["format"], "vimlop-contours");
  EXPECT_EQ(json["version"], 1);
  ASSERT_EQ(json["frames"].size(), 2u);
  EXPECT_EQ(json["frames"][0]["name"], "frame000.png");
  EXPECT_EQ(json["frames"][0]["points"], nlohmann::json::parse("[[10.5, 20.0, 0.0, -1.0]]"));
  EXPECT_TRUE(json["frames"][1]["points"].empty());
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
