#ifndef vimlop_OccludingContourDetector_h
#define vimlop_OccludingContourDetector_h

#include "ContourPoint.h"

#include "VIMLOPVideoModule.h"

#include <opencv2/core/mat.hpp>

#include <vector>

namespace vimlop
{

/// @brief The image channel the contour detector works on.
enum class ContourChannel
{
  /// Luminance (0.299 R + 0.587 G + 0.114 B).
  Luminance,
  /// Red only: haemoglobin absorbs green and blue far more than red, so
  /// vessels and most mucosal texture are faint in red while the light's
  /// fall-off with distance, which makes occluding contours, is not.
  Red
};

/**
 * @brief Finds occluding contours in an endoscopic frame, with their normals
 * (DESIGN §4, V1).
 *
 * With the light at the endoscope, the surface behind an occluding contour is
 * farther from the light than the surface in front of it, so it is darker by
 * the inverse-square fall-off: an occluding contour is a sharp step in the
 * logarithm of the intensity whose dark side stays dark well away from it.
 * The detector works on the log intensity (a ratio of intensities is then
 * the same step in bright and dark regions) of the red channel by default
 * (see ContourChannel), smooths it with a Gaussian (`smoothingSigmaPx`),
 * takes its gradient, thins the edges by non-maximum suppression along the
 * gradient and keeps the ones connected to a strong edge (hysteresis).
 * Texture and shading edges are then suppressed twice:
 * - by scale (`minScaleRatio`): a step keeps getting weaker as the smoothing
 *   grows, the mucosa's gradual shading and colour changes do not;
 * - by the dark-side test (`darkSideProbesPx`, `darkSideMinLogStep`): at
 *   every probe distance along the normal the far side must be darker than
 *   the near side (a vessel is dark only across its width, a contour's far
 *   side is dark all the way).
 * Chains shorter than `minChainLengthPx` are dropped. Each remaining edge
 * pixel is placed with sub-pixel accuracy along the gradient, gets the unit
 * negative gradient of the smoothed frame as its normal (pointing from the
 * near, brighter side to the far, darker side), and the points are thinned to
 * about one per `spacingPx`.
 */
class VIMLOPVIDEO_EXPORT OccludingContourDetector
{
public:
  /// @brief Parameters; pixels, and natural-log units of intensity.
  struct Options
  {
    /// The channel (default red).
    ContourChannel channel = ContourChannel::Red;
    /// Added to 8-bit intensities before the logarithm, grey levels (default
    /// 8), so sensor noise in dark regions does not become large steps.
    double logOffset = 8.0;
    /// Gaussian smoothing before the gradient, pixels (default 1.2).
    double smoothingSigmaPx = 1.2;
    /// Hysteresis thresholds on the log-intensity gradient, per pixel (defaults 0.04 and 0.02).
    double highThreshold = 0.04;
    double lowThreshold = 0.02;
    /// Scale test: least ratio of the gradient at smoothingSigmaPx to the
    /// strongest gradient nearby at twice that smoothing (default 1.2; 0
    /// disables the test). Smoothing halves the gradient of a step, such as
    /// a depth discontinuity, whenever it doubles, but hardly weakens the
    /// gradual shading and colour changes of the mucosa, which are wider
    /// than the smoothing.
    double minScaleRatio = 1.2;
    /// Distances along the normal at which the dark side is probed, pixels (default 3 and 7).
    std::vector<double> darkSideProbesPx = { 3.0, 7.0 };
    /// Least log-intensity drop from near to far side at every probe (default 0.08: 8 % darker).
    double darkSideMinLogStep = 0.08;
    /// Chains of edge pixels shorter than this are dropped, pixels (default 12).
    int minChainLengthPx = 12;
    /// Edge pixels this close to the image border are dropped, pixels (default 4).
    int borderPx = 4;
    /// Least distance between returned points, pixels (default 3; 0 returns
    /// every edge pixel, strongest first).
    double spacingPx = 3.0;
  };

  OccludingContourDetector();
  explicit OccludingContourDetector(const Options& options);

  const Options& options() const { return this->Opts; }

  /**
   * @brief The oriented contour points of an 8-bit BGR (or grey) frame.
   * @throws vimlop::Error for an empty frame or an unsupported pixel type.
   */
  std::vector<ContourPoint> detect(const cv::Mat& frame) const;

  /**
   * @brief Keeps points, in the given order, that lie at least `spacingPx`
   * from every point kept before them (detect() orders its points by edge
   * strength, so the best-localised ones are kept).
   */
  static std::vector<ContourPoint> thin(const std::vector<ContourPoint>& points, double spacingPx);

private:
  Options Opts;
};

} // namespace vimlop

#endif
