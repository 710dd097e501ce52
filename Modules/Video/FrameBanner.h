#ifndef vimlop_FrameBanner_h
#define vimlop_FrameBanner_h

#include <opencv2/core/mat.hpp>

#include <string>

namespace vimlop
{

/// @brief Height of the band underBanner() puts above a picture, px.
constexpr int frameBannerHeightPx = 30;

/// @brief The report's colours for a band (BGR): a pose to trust, one to
/// doubt, one not to use.
enum class BannerColour
{
  Green, ///< registered; tracking
  Amber, ///< not checked; degraded
  Red    ///< flagged as a failure; lost
};

/// @brief The BGR value of `colour`.
cv::Scalar bannerBgr(BannerColour colour);

/**
 * @brief `picture` (8-bit BGR) under a band of `colour` holding `text` in
 * white, so that a clip cut from a video still says whether its frames may
 * be trusted (the registered video's verdict, the tracked video's state).
 * A long text shrinks to the width, not below legibility; beyond, its end is cut.
 */
cv::Mat underBanner(const cv::Mat& picture, BannerColour colour, const std::string& text);

} // namespace vimlop

#endif
