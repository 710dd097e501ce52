#include <vimlop/Video/FrameContoursIO.h>

#include <vimlop/Core/AtomicFile.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

namespace vimlop
{

void writeFrameContours(const std::vector<FrameContours>& frames, const std::string& path)
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
    { "frames", list } };
  writeFileAtomically(path, document.dump(2) + "\n");
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
