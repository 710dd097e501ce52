#include <vimlop/Video/FrameBanner.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>

namespace vimlop
{

cv::Scalar bannerBgr(BannerColour colour)
{
  switch (colour)
  {
    case BannerColour::Amber:
      return cv::Scalar(0, 98, 122);
    case BannerColour::Red:
      return cv::Scalar(27, 22, 179);
    case BannerColour::Green:
      break;
  }
  return cv::Scalar(46, 122, 27);
}

cv::Mat underBanner(const cv::Mat& picture, BannerColour colour, const std::string& text)
{
  cv::Mat framed(picture.rows + frameBannerHeightPx, picture.cols, CV_8UC3, bannerBgr(colour));
  picture.copyTo(framed(cv::Rect(0, frameBannerHeightPx, picture.cols, picture.rows)));
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  int baseline = 0;
  double scale = 0.6;
  const cv::Size size = cv::getTextSize(text, font, scale, 1, &baseline);
  scale = std::max(0.35, std::min(scale, scale * (picture.cols - 16) / std::max(1, size.width)));
  cv::putText(framed, text, cv::Point(8, frameBannerHeightPx - 10), font, scale,
    cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  return framed;
}

} // namespace vimlop
