#ifndef vimlop_FrameBanner_h
#define vimlop_FrameBanner_h

#include <opencv2/core/mat.hpp>

#include <string>

namespace vimlop
{

/// @brief Height of the band underBanner() puts above a picture, px.
constexpr int frameBannerHeightPx = 30;

/**
 * @brief `picture` (8-bit BGR) under a band of `colourBgr` holding `text` in
 * white, so that a clip cut from a video still says whether its frames may
 * be trusted (the registered video's verdict, the tracked video's state).
 * A long text shrinks to the width, not below legibility; beyond, its end is cut.
 */
cv::Mat underBanner(const cv::Mat& picture, const cv::Scalar& colourBgr, const std::string& text);

} // namespace vimlop

#endif
