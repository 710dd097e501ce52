#ifndef vimlop_KltFeatureTracker_h
#define vimlop_KltFeatureTracker_h

#include <Eigen/Core>

#include <opencv2/core/mat.hpp>

#include <vector>

namespace vimlop
{

/// @brief Settings of KltFeatureTracker.
struct KltFeatureTrackerOptions
{
  /// Side of the window matched around each feature, px (default 21, odd, at least 5).
  int windowPx = 21;
  /// Pyramid levels above the full image (default 3): a level halves the
  /// picture, so a feature can move about windowPx * 2^levels / 2 between frames.
  int pyramidLevels = 3;
  /// A feature is kept only when tracking it back from the new frame lands
  /// within this distance of where it started, px (default 0.5). This
  /// forward-backward check drops features that slid along an edge or onto
  /// a highlight.
  double maxForwardBackwardPx = 0.5;
  /// Corners weaker than this fraction of the frame's strongest are not
  /// detected (default 0.01, OpenCV's goodFeaturesToTrack quality level).
  double cornerQuality = 0.01;
  /// Scale of the illumination divided out of every frame before tracking
  /// and detection, px (default 8; 0: none): each pixel minus its local mean,
  /// over its local standard deviation, both in Gaussian windows of this
  /// sigma. The endoscope carries its light, so a patch brightens as the
  /// scope nears it; Lucas-Kanade assumes constant brightness and would slide.
  double illuminationSigmaPx = 8.0;
  /// Least distance between detected corners, and between a new corner and a
  /// feature already tracked, px (default 8).
  double minCornerDistancePx = 8.0;

  /// @throws vimlop::Error naming the first value out of range.
  void validate() const;
};

/**
 * @brief Frame-to-frame tracking of image features (pyramidal Lucas-Kanade
 * optical flow with a forward-backward check) and detection of new corners
 * (Shi-Tomasi).
 *
 * It holds the current frame only; the caller owns the features and what
 * they stand for (a tracker's map points). Frames are 8-bit BGR or grey, all
 * of one size.
 */
class KltFeatureTracker
{
public:
  /// @throws vimlop::Error for invalid options.
  explicit KltFeatureTracker(const KltFeatureTrackerOptions& options = {});

  /// @brief Makes `frame` the current frame without tracking anything.
  /// @throws vimlop::Error for an empty frame or one that is not 8-bit with 1 or 3 channels.
  void reset(const cv::Mat& frame);

  /**
   * @brief Tracks `pixels` of the current frame into `frame`, which becomes
   * the current frame. On return `pixels` holds where each feature went;
   * `kept[i]` is 0 for a feature that was lost (its pixel is then
   * meaningless): no match, out of the image, or failing the
   * forward-backward check.
   * @throws vimlop::Error before reset(), for a frame of another size, or as reset().
   */
  std::vector<char> track(const cv::Mat& frame, std::vector<Eigen::Vector2d>& pixels);

  /**
   * @brief Up to `count` corners of the current frame, strongest first, where
   * `mask` is non-zero (empty: everywhere) and at least half a window from
   * the border, at least minCornerDistancePx from each other and from the
   * pixels of `existing`.
   * @throws vimlop::Error before reset() or for a mask of another size.
   */
  std::vector<Eigen::Vector2d> detect(
    int count, const std::vector<Eigen::Vector2d>& existing, const cv::Mat& mask = cv::Mat()) const;

private:
  /// The frame as tracked: grey, its illumination divided out.
  cv::Mat prepared(const cv::Mat& frame) const;

  KltFeatureTrackerOptions Options;
  cv::Mat Current; ///< prepared
};

} // namespace vimlop

#endif
