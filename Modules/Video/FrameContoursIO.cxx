#include <vimlop/Video/FrameContoursIO.h>

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/FileError.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <fstream>

namespace vimlop
{

void writeFrameContours(const std::vector<FrameContours>& frames,
  const FrameContoursPictures& pictures, const std::string& path)
{
  nlohmann::json list = nlohmann::json::array();
  for (const FrameContours& frame : frames)
  {
    nlohmann::json points = nlohmann::json::array();
    for (const ContourPoint& p : frame.points)
    {
      points.push_back({ p.pixel.x(), p.pixel.y(), p.normal.x(), p.normal.y() });
    }
    list.push_back({ { "name", frame.name }, { "points", points } });
  }
  const nlohmann::json document = { { "format", "vimlop-contours" }, { "version", 1 },
    { "convention",
      "pixels with the centre of the top-left pixel at (0, 0); [u, v, nu, nv] with the unit normal "
      "pointing from the near, occluding side to the far side" },
    { "width", pictures.widthPx }, { "height", pictures.heightPx },
    { "undistorted", pictures.undistorted }, { "frames", list } };
  writeFileAtomically(path, document.dump(2) + "\n");
}

std::vector<FrameContours> readFrameContours(
  const std::string& path, FrameContoursPictures* pictures)
{
  std::ifstream in(path);
  if (!in)
  {
    throwFileError(path, "cannot open the contours file");
  }
  nlohmann::json document;
  try
  {
    document = nlohmann::json::parse(in);
  }
  catch (const nlohmann::json::exception&)
  {
    throwFileError(path, "not a JSON file");
  }
  if (!document.is_object() || document.value("format", "") != "vimlop-contours")
  {
    throwFileError(
      path, "not a contours file of vimlop contours (its \"format\" is not \"vimlop-contours\")");
  }
  std::vector<FrameContours> frames;
  try
  {
    if (pictures)
    {
      pictures->widthPx = document.value("width", 0);
      pictures->heightPx = document.value("height", 0);
      pictures->undistorted = document.value("undistorted", false);
    }
    for (const nlohmann::json& frame : document.at("frames"))
    {
      FrameContours f;
      f.name = frame.at("name").get<std::string>();
      for (const nlohmann::json& point : frame.at("points"))
      {
        if (!point.is_array() || point.size() != 4)
        {
          throwFileError(path, "frame '" + f.name + "': a point is not [u, v, nu, nv]");
        }
        ContourPoint p;
        p.pixel = { point[0].get<double>(), point[1].get<double>() };
        p.normal = { point[2].get<double>(), point[3].get<double>() };
        if (!p.pixel.allFinite() || !(std::abs(p.normal.norm() - 1.0) < 1e-3))
        {
          throwFileError(path,
            "frame '" + f.name +
              "': a point's pixel is not finite or its normal is not a unit "
              "vector");
        }
        f.points.push_back(p);
      }
      frames.push_back(std::move(f));
    }
  }
  catch (const nlohmann::json::exception& e)
  {
    throwFileError(path, std::string("malformed: ") + e.what());
  }
  return frames;
}

cv::Mat drawFrameContours(const cv::Mat& frame, const std::vector<ContourPoint>& points)
{
  cv::Mat picture = frame.clone();
  for (const ContourPoint& p : points)
  {
    const cv::Point2d a(p.pixel.x(), p.pixel.y());
    const cv::Point2d b = a + 4.0 * cv::Point2d(p.normal.x(), p.normal.y());
    cv::line(picture, a, b, cv::Scalar(255, 255, 0), 1, cv::LINE_AA);
    cv::circle(picture, a, 1, cv::Scalar(0, 255, 0), -1, cv::LINE_AA);
  }
  return picture;
}

} // namespace vimlop
